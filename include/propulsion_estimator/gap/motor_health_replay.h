#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/estimation/motor_health.h"
#include "propulsion_estimator/logs/flight_streams.h"
#include "propulsion_estimator/model/propulsion_model.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace gap {

/// What the node's onboard motor-health check (estimation/motor_health.h) said over one flight:
/// how many times (once a second) it judged a full window, the channels it flagged (each once, in
/// the order first flagged) and when it first did, in s on the flight's clock (NaN: never).
struct MotorHealthReplay {
  int judgements = 0;  ///< full windows judged, once a second
  std::vector<int> flagged_channels;  ///< flagged channels, 1-based, each once, in the order first flagged
  double first_flag_s = 0.0;  ///< s on the flight's clock; NaN when none was flagged
};

/// Replays a flight's logged streams through the core Estimator (default configuration, the
/// model's channels 1..motors) and the motor-health check as estimator_node feeds them: battery,
/// IMU and velocity as they arrived, the check after each accepted RCOut message, its
/// verdict taken once a second.
MotorHealthReplay replayMotorHealth(const PropulsionModel& model, const Vehicle& vehicle, const FlightStreams& streams,
                                    const MotorHealthConfig& config = {});

/// motor_health.yaml of diagnose_gap: per flight (named as in `names`) the judgements, the
/// flagged channels and the first flag's time (null when none).
std::string motorHealthReplayYaml(const std::vector<std::string>& names, const std::vector<MotorHealthReplay>& replays);

}  // namespace gap
}  // namespace propulsion_estimator
