#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/logs/flight_streams.h"
#include "propulsion_estimator/model/propulsion_model.h"
#include "propulsion_estimator/onboard/model_check.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace gap {

/// What the node's live model check (onboard/model_check.h, issue 21) said over one flight with
/// ESC telemetry: how many times (once a second) it judged the motors, the verdicts other than
/// "consistent" it gave (each once, in the order given) with the channels it flagged, and when it
/// first did, in s on the flight's clock (NaN: never).
struct ModelCheckReplay {
  bool telemetry = false;  ///< whether the flight had ESC telemetry at all
  int judgements = 0;  ///< reports with every motor judged, once a second
  std::vector<std::string> verdicts;  ///< "propeller", "motor_esc", "supply": each once
  std::vector<int> flagged_channels;  ///< 1-based, each once, in the order first flagged
  double first_flag_s = kNaN;  ///< s on the flight's clock; NaN when nothing was flagged
  /// Per rotor, the mean over the judgements of MotorCheck::rpm_deviation and current_deviation
  /// (against the baseline, where the model's reference holds one); empty when never judged.
  std::vector<double> rpm_deviation;
  std::vector<double> current_deviation;  ///< see rpm_deviation
  /// The mean over the judgements of the motors' median rpm against the model
  /// (ModelCheckReport::median_rpm_ratio); NaN when never judged.
  double median_rpm_ratio = kNaN;
};

/// Replays a flight's logged streams through the core Estimator (default configuration, channels
/// 1..motors) and the model check (`config`) as estimator_node feeds them: battery, IMU, velocity
/// and ESC telemetry as they arrived, the estimate after each accepted RCOut message, the
/// report taken once a second. Without ESC telemetry nothing is judged. Where the model's
/// motor_reference holds ESC deviations, the motors are judged by their change from them, as the
/// node does.
ModelCheckReplay replayModelCheck(const PropulsionModel& model, const Vehicle& vehicle, const FlightStreams& streams,
                                  const ModelCheckConfig& config = {});

/// model_check.yaml of diagnose_gap: per flight (named as in `names`) whether it had telemetry,
/// the judgements, the verdicts, the flagged channels and the first flag's time (null when none).
std::string modelCheckReplayYaml(const std::vector<std::string>& names, const std::vector<ModelCheckReplay>& replays);

}  // namespace gap
}  // namespace propulsion_estimator
