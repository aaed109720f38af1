#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/estimation/binned_window.h"
#include "propulsion_estimator/estimation/running_moments.h"

namespace propulsion_estimator {

/// When is the vehicle hovering? Total thrust steady over a sliding window and, where an IMU or a
/// velocity source is available, small tilt, vertical speed and vertical acceleration; in the
/// spirit of ArduPilot's hover-throttle learning (vertical speed under 0.6 m/s, tilt under 5 deg).
struct HoverConfig {
  double window_s = 2.0;  ///< s; length of the sliding window
  /// Fraction of window_s the samples must span; at most 1 - 1/64 (the window's bins, see
  /// BinnedWindow).
  double min_window_fill = 0.8;
  double max_thrust_rel_std = 0.05;      ///< std / mean of vertical thrust over the window
  double max_tilt_deg = 5.0;  ///< deg; largest tilt from level in the window
  double max_vertical_speed_m_s = 0.6;  ///< m/s; largest vertical speed in the window
  double max_vertical_accel_m_s2 = 1.0;  ///< of the window's mean vertical acceleration
  double min_mass_kg = 0.3;              ///< the thrust must carry at least this: not idling on the ground

  void validate() const;  ///< ConfigError naming the field
};

/// One sample; NaN marks what is not measured (no fresh IMU, no fresh vertical speed source).
struct HoverSample {
  double vertical_thrust_n = 0.0;  ///< N
  double mass_kg = 0.0;  ///< mass that thrust holds
  double tilt_rad = 0.0;  ///< tilt from level, rad
  double vertical_speed_m_s = 0.0;  ///< m/s, up positive
  double vertical_accel_m_s2 = 0.0;  ///< m/s^2, world vertical, gravity removed
};

/// Why the window is not a hover (the first condition that failed); kNone when it is.
enum class HoverBlocker {
  /// The window is not full yet, the thrust is too low, unsteady, the vehicle tilted, climbing or
  /// sinking, or accelerating vertically (the first check that failed).
  ///@{
  kNone,
  kWindowFilling,
  kLowThrust,
  kThrustUnsteady,
  kTilted,
  kClimbingOrSinking,
  kAccelerating,
  ///@}
  kSignalGap,  ///< a check's signal measured on some samples of the window only (it went stale)
  kExpired,  ///< no sample within window_s before now: the last verdict is no longer one
};

/// The hover checks that need a signal besides the thrust, as bits of a mask.
enum HoverCheck : std::uint8_t {
  kTiltCheck = 1,           ///< needs the IMU's attitude
  kVerticalSpeedCheck = 2,  ///< needs a velocity or barometric vertical speed
  kVerticalAccelCheck = 4,  ///< needs the IMU's acceleration
};
/// "tilt, vertical speed": the checks of `mask`, or "none".
std::string hoverCheckNames(std::uint8_t mask);

/// What the hover window holds about its samples (the Aggregate of its BinnedWindow).
struct HoverStatistics {
  RunningMoments thrust_n;  ///< mean and spread of the vertical thrust, N
  double mass_sum_kg = 0.0;  ///< sum of the samples' masses, kg
  double max_tilt_rad = kNaN;  ///< NaN until a sample has one
  std::uint64_t tilt_samples = 0;  ///< samples that had a tilt
  double max_abs_vertical_speed_m_s = kNaN;  ///< NaN until a sample has one
  std::uint64_t vertical_speed_samples = 0;  ///< samples that had a vertical speed
  double vertical_accel_sum_m_s2 = 0.0;  ///< sum of the samples' vertical accelerations, m/s^2
  std::uint64_t vertical_accel_samples = 0;  ///< samples that had a vertical acceleration

  void add(const HoverSample& sample);  ///< adds one sample; NaN fields are not counted
  void merge(const HoverStatistics& other);  ///< adds the statistics of another part of the window
};

/// The detector's verdict on its window, with the window statistics it was based on (SI units).
struct HoverVerdict {
  bool hovering = false;  ///< whether the window is a hover
  HoverBlocker blocker = HoverBlocker::kWindowFilling;  ///< the first check that failed; kNone when hovering
  std::size_t samples = 0;  ///< samples in the window
  double span_s = 0.0;  ///< s between the oldest and the newest sample
  double mean_thrust_n = 0.0;  ///< N, vertical
  double thrust_rel_std = 0.0;  ///< std / mean of the vertical thrust
  double mean_mass_kg = 0.0;  ///< kg, the mass the mean vertical thrust holds
  double max_tilt_rad = 0.0;            ///< NaN without IMU
  double max_abs_vertical_speed_m_s = 0.0;  ///< NaN without velocity
  double mean_vertical_accel_m_s2 = 0.0;    ///< NaN without IMU
  /// Samples of the window that had each signal (for kSignalGap).
  ///@{
  std::size_t tilt_samples = 0;
  std::size_t vertical_speed_samples = 0;
  std::size_t vertical_accel_samples = 0;
  ///@}

  /// The checks whose signal no sample of the window had (HoverCheck bits): they did not take
  /// part in the verdict.
  std::uint8_t inactiveChecks() const {
    return static_cast<std::uint8_t>((tilt_samples == 0 ? kTiltCheck : 0) |
                                     (vertical_speed_samples == 0 ? kVerticalSpeedCheck : 0) |
                                     (vertical_accel_samples == 0 ? kVerticalAccelCheck : 0));
  }
};

/// One line for humans: "hovering: ..." or "not hovering: <why>, <window statistics>".
std::string describe(const HoverVerdict& verdict, const HoverConfig& config);

/// Keeps a sliding window of HoverSample statistics and judges it against a HoverConfig. The
/// window is sized by time (BinnedWindow): any sample rate works, in fixed memory.
class HoverDetector {
 public:
  /// `config` validated by its owner (EstimatorConfig::validate).
  explicit HoverDetector(const HoverConfig& config);

  /// Adds a sample and returns the verdict over the window, in O(1). Allocates nothing.
  const HoverVerdict& add(double stamp_s, const HoverSample& sample);
  /// The verdict after the last sample.
  const HoverVerdict& verdict() const { return verdict_; }
  /// As given.
  const HoverConfig& config() const { return config_; }
  void clear();  ///< forgets the window; the verdict starts over (kWindowFilling)
  /// Forgets the window because no sample came within window_s: the verdict says kExpired.
  void expire();

 private:
  void evaluate();

  HoverConfig config_;
  BinnedWindow<HoverStatistics> window_;
  HoverVerdict verdict_;
};

}  // namespace propulsion_estimator
