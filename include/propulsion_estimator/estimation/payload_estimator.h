#pragma once

#include <cstddef>
#include <cstdint>

#include "propulsion_estimator/estimation/binned_window.h"
#include "propulsion_estimator/estimation/running_moments.h"

namespace propulsion_estimator {

/// Thesis eq. 2.1-2.3: in hover the motors' thrust equals the weight; the payload is the total
/// minus the empty weight recorded before. Single readings were up to 29 % off in the thesis, so
/// the estimate is the mean over the hover samples of the current hover episode (at most
/// averaging_window_s of them, kept as a BinnedWindow: any rate, fixed memory); a pause in hovering longer than episode_gap_s starts a new
/// episode, since the payload may change between hovers (picked up on a cable, or after landing).
struct PayloadConfig {
  double averaging_window_s = 10.0;  ///< s; at most this much of the hover episode is averaged
  std::size_t min_samples = 25;  ///< before a mean is reported
  double episode_gap_s = 1.0;  ///< s; a pause in hovering longer than this starts a new episode

  void validate() const;  ///< ConfigError naming the field
};

/// Where the empty mass came from: nowhere yet, the URDF, a node parameter, a tare file or a tare
/// taken in this run.
enum class EmptyMassSource { kNone, kUrdf, kParameter, kTareFile, kTare };
/// "none", "urdf", "parameter", "tare_file", "tare".
const char* emptyMassSourceName(EmptyMassSource source);

/// The estimate's state: no total mass yet, a total but no empty mass, hovering (the payload is
/// being averaged), or holding the last hover's payload.
enum class PayloadState { kWaitingForHover, kNoTareYet, kHovering, kHolding };
/// "waiting_for_hover", "no_tare_yet", "hovering", "holding".
const char* payloadStateName(PayloadState state);

/// The payload estimate after a sample: total, empty and payload mass in kg (NaN where unknown),
/// the spread of the total and the averaging window behind it.
struct MassEstimate {
  PayloadState state = PayloadState::kWaitingForHover;  ///< what the estimate rests on
  bool hovering = false;  ///< whether the last sample was a hover
  double total_mass_kg = 0.0;  ///< NaN until min_samples hover samples
  double mass_std_kg = 0.0;  ///< standard deviation of the total mass over the window, kg
  double empty_mass_kg = 0.0;  ///< NaN when unknown
  EmptyMassSource empty_mass_source = EmptyMassSource::kNone;  ///< where the empty mass came from
  double payload_mass_kg = 0.0;  ///< NaN without total and empty mass
  double window_s = 0.0;  ///< s the averaged samples span
  std::uint32_t window_samples = 0;  ///< samples averaged
};

/// Averages the hover samples' total mass over the current hover episode and subtracts the empty
/// mass (thesis eq. 2.1-2.3, see PayloadConfig).
class PayloadEstimator {
 public:
  /// `config` validated by its owner (EstimatorConfig::validate).
  explicit PayloadEstimator(const PayloadConfig& config);

  /// The mass the thrust holds at `stamp_s`, and whether the vehicle hovers. O(1), allocates nothing.
  const MassEstimate& add(double stamp_s, double mass_kg, bool hovering);
  /// The estimate after the last sample.
  const MassEstimate& estimate() const { return estimate_; }

  /// Sets the empty mass, kg, and where it came from; the payload follows.
  void setEmptyMass(double mass_kg, EmptyMassSource source);
  void clearEmptyMass();  ///< forgets the empty mass (the payload becomes NaN)
  /// Forgets the hover samples (landing, clock reset, reset service).
  void clearWindow();
  /// The hover ended without a sample saying so (its verdict expired): the average is held.
  void endHover();

 private:
  /// The window's statistics change only when a sample is added or the window cleared; the state
  /// also when hovering starts or stops, or the empty mass changes.
  void updateStatistics();
  void updateState(bool hovering);

  PayloadConfig config_;
  BinnedWindow<RunningMoments> window_;
  double last_hover_stamp_s_ = 0.0;
  bool hovered_before_ = false;
  MassEstimate estimate_;
};

}  // namespace propulsion_estimator
