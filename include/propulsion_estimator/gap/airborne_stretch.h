#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/logs/flight_manifest.h"
#include "propulsion_estimator/logs/flight_streams.h"
#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {
namespace gap {

/// How the airborne stretches of a flight weighed as a whole (a manifest's `mass_kg:` instead of
/// segments) are found in its log. Armed: every motor above disarmed_pwm_max_us, no gap in RCOut
/// over max_gap_s. Airborne: a run of RCOut messages of an armed stretch whose model thrust holds
/// at least lift_fraction of the mass that stretch mostly holds (its 75th percentile), dips shorter
/// than max_dip_s (a fast descent's start) bridged: a vehicle on its feet, spinning up or landed,
/// holds far less. The weighed
/// segment leaves out settle_s after lift-off (the payload leaving the ground, the climb's
/// transient) and end_margin_s before touchdown.
struct AirborneSettings {
  double disarmed_pwm_max_us = 950.0;  ///< us, as the node's parameter of that name
  double max_gap_s = 1.0;  ///< s
  double lift_fraction = 0.8;  ///< of the stretch's 75th-percentile held mass
  double max_dip_s = 3.0;  ///< s below it that stay airborne
  double settle_s = 4.0;  ///< s after lift-off
  double end_margin_s = 1.0;  ///< s before touchdown
  double min_weighed_s = 5.0;  ///< s; a shorter stretch is a hop, not a flight

  /// Throws FieldError naming the field for a value outside its range.
  void validate() const;
};

/// One airborne stretch: when the vehicle left the ground and came back, and the span weighed.
struct AirborneStretch {
  double lift_off_s = 0.0;   ///< s on the log's clock
  double touchdown_s = 0.0;  ///< s
  double start_s = 0.0;      ///< lift_off_s + settle_s
  double end_s = 0.0;        ///< touchdown_s - end_margin_s
};

/// The airborne stretches of `streams`, in time order: RCOut with each message's voltage (the
/// newest battery reading) through `model`'s thrust, the sum over `motors` rotors. Empty when there
/// is none, with `why` (when given) saying what the log held instead, with its numbers.
std::vector<AirborneStretch> findAirborneStretches(const FlightStreams& streams, const PropulsionModel& model,
                                                   const AirborneSettings& settings, std::string* why = nullptr);

/// The weighed segments of a flight given as `mass_kg` per airborne stretch: one mass for every
/// stretch, or one per stretch in order. Throws DataError "<source>: ..." when no stretch was found
/// (with why) or the masses given do not match the stretches found.
std::vector<ManifestSegment> airborneSegments(const FlightStreams& streams, const PropulsionModel& model,
                                              const std::vector<double>& mass_kg, const AirborneSettings& settings,
                                              std::vector<AirborneStretch>* stretches = nullptr);

}  // namespace gap
}  // namespace propulsion_estimator
