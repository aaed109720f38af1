#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/estimation/motor_health.h"
#include "propulsion_estimator/offline/flight_estimate.h"

namespace propulsion_estimator {
namespace offline {

/// What `estimate` keeps of one flight for machines (its `flight.yaml`, which `fleet` reads): the
/// hovers, the motor-health verdict with every rotor's gap, the pack's resistance and the live ESC
/// check's verdict and supply resistance, the warnings. SI units; a NaN figure is an absent key.
/// @code{.yaml}
/// format: propulsion_estimator/flight_record
/// version: 1
/// source: logs/v03/flight_012.bag
/// duration_s: 71.3
/// empty_mass_kg: 1.315
/// hovers: [{start_s: 9.1, end_s: 31.0, total_mass_kg: 1.482, mass_std_kg: 0.004, payload_kg: 0.167, ...}]
/// motor_health: {judged: true, blocks: 10, flagged_channel: 0, motors: [{channel: 1, thrust_gap: 0.004, thrust_gap_std: 0.006}, ...]}
/// pack: {internal_resistance_ohm: 0.031, internal_resistance_std_ohm: 0.002}
/// esc: {verdict: consistent, flagged_channel: 0, supply_resistance_ohm: 0.011}
/// log_damage: ""   # or the reader's line where a damaged log stopped
/// warnings: []
/// @endcode
struct FlightRecord {
  std::string source;  ///< the log
  double duration_s = 0.0;  ///< s from the log's first message to its last
  double empty_mass_kg = kNaN;  ///< kg; NaN when unknown
  std::vector<HoverEpisode> hovers;  ///< in time order
  MotorHealthVerdict motor_health;  ///< the last judged window (judged false: why not)
  std::vector<int> flagged_channels;  ///< every channel the motor-health check flagged
  double pack_resistance_ohm = kNaN;  ///< ohm; the pack's at the end of the log (NaN: not identified)
  double pack_resistance_std_ohm = kNaN;  ///< ohm; one standard deviation
  std::string esc_verdict = "not_judged";  ///< the live ESC check's last verdict (modelCheckVerdictName)
  int esc_flagged_channel = 0;  ///< its channel, 0: none
  double supply_resistance_ohm = kNaN;  ///< ohm; battery to ESCs, from ESC telemetry
  std::vector<std::string> esc_flags;  ///< every verdict other than consistent, first first
  std::string log_damage;  ///< where the log is damaged and was read up to; "" for a whole log
  std::vector<std::string> warnings;  ///< one line each
};

/// The record of `estimate` (its samples left out).
FlightRecord flightRecordOf(const FlightEstimate& estimate);
/// The file's text (numbers to the last bit, so that it reads back identical).
std::string flightRecordText(const FlightRecord& record);
/// The record in a flight.yaml's text. ConfigError "<source>:<line>: <key>: <problem>" for content
/// that is not one: another format or version, an unknown or missing key, a channel below 1.
FlightRecord parseFlightRecord(const std::string& text, const std::string& source);

}  // namespace offline
}  // namespace propulsion_estimator
