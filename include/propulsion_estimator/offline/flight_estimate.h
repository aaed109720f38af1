#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/estimation/motor_health.h"
#include "propulsion_estimator/logs/flight_streams.h"
#include "propulsion_estimator/model/propulsion_model.h"
#include "propulsion_estimator/onboard/capability.h"
#include "propulsion_estimator/onboard/model_check.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace offline {

/// How a logged flight is estimated: the node's configuration (its defaults but for these) and how
/// often the estimates are kept.
struct EstimateOptions {
  EstimatorConfig estimator;  ///< motor channels 1..n and the node's defaults (replayEstimatorConfig)
  CapabilityConfig capability;  ///< the node's defaults: min thrust-to-weight 1.6, no battery
  ModelCheckConfig esc_telemetry;  ///< the live ESC check's (the node's esc_telemetry/...) defaults
  /// Rows kept per second of the log's clock, as the node's publish_rate_hz limits ~payload (0: every
  /// accepted RCOut message). Hover episodes are judged on every message whatever the rate.
  double sample_rate_hz = 10.0;

  /// Throws FieldError naming "sample_rate_hz" (0..1000 Hz) or the estimator's or capability's field.
  void validate(std::size_t rotors) const;
};

/// The estimates at one kept RCOut message, SI units, as the node publishes them on ~totals and
/// ~payload. Masses are NaN where the node publishes NaN.
struct EstimateSample {
  double time_s = 0.0;  ///< s on the log's clock
  double voltage_v = 0.0;  ///< the battery voltage the motors were evaluated at, V
  double thrust_n = 0.0;  ///< summed thrust, N
  double current_a = 0.0;  ///< summed modelled current, A (NaN without a current surface)
  double power_w = 0.0;  ///< summed modelled power, W (NaN without)
  double lifted_mass_kg = 0.0;  ///< the mass this message's vertical thrust holds, kg (not averaged)
  bool hovering = false;  ///< the hover detector's verdict
  double total_mass_kg = 0.0;  ///< the hover average (the node's ~payload total_mass_kg), kg
  double mass_std_kg = 0.0;  ///< its standard deviation over the window, kg
  double payload_kg = 0.0;  ///< total less the empty mass, kg
  int motors_out_of_domain = 0;  ///< motors outside the model's domain
  std::vector<double> motor_thrust_n;  ///< per rotor, N
};

/// One stretch of hover (hover samples no further apart than payload/episode_gap_s) and what the
/// node said at its last sample: the averaged mass and payload, and the capability at that moment.
struct HoverEpisode {
  double start_s = 0.0;  ///< s on the log's clock, first hover sample
  double end_s = 0.0;    ///< last hover sample
  double total_mass_kg = 0.0;  ///< the hover average at end_s; NaN when the episode was too short to average
  double mass_std_kg = 0.0;    ///< kg
  double payload_kg = 0.0;     ///< NaN without an empty mass
  double window_s = 0.0;       ///< s of hover the average spans
  double voltage_v = 0.0;      ///< V at end_s
  double thrust_to_weight = 0.0;  ///< all motors at the top of the PWM range over the hover weight
  double max_additional_payload_kg = 0.0;  ///< keeping the capability's min thrust-to-weight; NaN where not computed
};

/// What the node would have said over a whole logged flight.
struct FlightEstimate {
  std::string source;  ///< the log
  double duration_s = 0.0;  ///< s from the log's first message to its last
  std::vector<EstimateSample> samples;  ///< at EstimateOptions::sample_rate_hz
  std::vector<HoverEpisode> hovers;  ///< in time order
  EstimatorCounters counters;  ///< inputs accepted and refused
  double empty_mass_kg = 0.0;  ///< NaN when unknown (no option, no URDF inertials)
  std::string empty_mass_source;  ///< "parameter", "urdf", "none"
  MotorHealthVerdict motor_health;  ///< the last judged window (judged false: why not)
  std::vector<int> flagged_channels;  ///< every channel the motor-health check flagged, first flag first
  /// The pack's internal resistance at the end of the log (the capability's battery estimate, with
  /// capability/battery/... configured and the log carrying the current), ohm; NaN when not identified.
  double pack_resistance_ohm = kNaN;
  double pack_resistance_std_ohm = kNaN;  ///< ohm; one standard deviation
  /// The live ESC check's last judgement (its verdict not_judged: never judged, and why in its note).
  ModelCheckReport esc_check;
  /// Every verdict other than consistent the ESC check gave, as "propeller on channel 2" or
  /// "supply", first first.
  std::vector<std::string> esc_flags;
  /// Where the log is damaged and was read up to (the reader's line); "" for a whole log.
  std::string log_damage;
  /// One line each, with the numbers: refused inputs, readings outside the model's domain (with the
  /// log's and the model's ranges), no hover and why, flagged motors.
  std::vector<std::string> warnings;
};

/// Runs the node's onboard session (the estimator's hover detection, mass and payload, the motor
/// health check, the live ESC check and the capability) on `streams` message by message, in the order a replayed bag
/// hands them to the node (FlightFeed). Throws ConfigError when the options do not fit the vehicle
/// (see EstimateOptions::validate).
FlightEstimate estimateFlight(const PropulsionModel& model, const Vehicle& vehicle, const FlightStreams& streams,
                              const EstimateOptions& options);
/// What estimateFlight() refuses before it reads a message: options that do not fit the vehicle, or
/// a session the model and the vehicle cannot make (a motor reference for other rotors).
/// ConfigError as estimateFlight; nothing when a log would be estimated.
void checkEstimateInputs(const PropulsionModel& model, const Vehicle& vehicle, const EstimateOptions& options);

}  // namespace offline
}  // namespace propulsion_estimator
