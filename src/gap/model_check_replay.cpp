#include "propulsion_estimator/gap/model_check_replay.h"

#include <algorithm>
#include <cmath>

#include <yaml-cpp/yaml.h>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/offline/flight_feed.h"
#include "add_once.h"

namespace propulsion_estimator {
namespace gap {
ModelCheckReplay replayModelCheck(const PropulsionModel& model, const Vehicle& vehicle, const FlightStreams& streams,
                                  const ModelCheckConfig& config) {
  OnboardSession session(model, vehicle, offline::replayOnboardConfig(vehicle, {}, config));
  ModelCheckReplay replay;
  replay.telemetry = !streams.esc.empty();
  if (!replay.telemetry) return replay;
  const std::size_t motors = vehicle.rotors.size();
  std::vector<double> rpm_sum(motors, 0.0), current_sum(motors, 0.0);
  double level_sum = 0.0;
  double next_report_s = 0.0;
  const offline::FlightFeed feed(streams);
  for (const offline::Arrival& a : feed.arrivals()) {
    if (!feed.feed(a, &session)) continue;
    if (a.time_s < next_report_s) continue;
    next_report_s = a.time_s + 1.0;
    const ModelCheckReport report = session.modelCheck().report(a.time_s);
    if (report.verdict == ModelCheckVerdict::kNotJudged) continue;
    ++replay.judgements;
    level_sum += report.median_rpm_ratio;
    for (std::size_t k = 0; k < motors; ++k) {
      rpm_sum[k] += report.motors[k].rpm_deviation;
      current_sum[k] += report.motors[k].current_deviation;
    }
    if (report.verdict == ModelCheckVerdict::kConsistent) continue;
    if (replay.verdicts.empty()) replay.first_flag_s = a.time_s;
    addOnce(&replay.verdicts, std::string(modelCheckVerdictName(report.verdict)));
    if (report.flagged_channel != 0) addOnce(&replay.flagged_channels, report.flagged_channel);
  }
  if (replay.judgements > 0) replay.median_rpm_ratio = level_sum / replay.judgements;
  for (std::size_t k = 0; replay.judgements > 0 && k < motors; ++k) {
    replay.rpm_deviation.push_back(rpm_sum[k] / replay.judgements);
    replay.current_deviation.push_back(current_sum[k] / replay.judgements);
  }
  return replay;
}

std::string modelCheckReplayYaml(const std::vector<std::string>& names, const std::vector<ModelCheckReplay>& replays) {
  YAML::Emitter out;
  out << YAML::Comment("estimator_node's live model check of ESC telemetry (/diagnostics, ~capability) replayed on "
                       "each flight");
  out << YAML::BeginMap << YAML::Key << "flights" << YAML::Value << YAML::BeginSeq;
  for (std::size_t i = 0; i < replays.size(); ++i) {
    const ModelCheckReplay& replay = replays[i];
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "bag" << YAML::Value << names[i] << YAML::Key << "telemetry"
        << YAML::Value << replay.telemetry << YAML::Key << "judgements" << YAML::Value << replay.judgements
        << YAML::Key << "verdicts" << YAML::Value << YAML::Flow << replay.verdicts << YAML::Key << "flagged"
        << YAML::Value << YAML::Flow << replay.flagged_channels << YAML::Key << "first_flag_s" << YAML::Value;
    if (std::isnan(replay.first_flag_s)) {
      out << YAML::Null;
    } else {
      out << replay.first_flag_s;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace gap
}  // namespace propulsion_estimator
