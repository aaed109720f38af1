#include "propulsion_estimator/gap/motor_health_replay.h"

#include <algorithm>
#include <cmath>

#include <yaml-cpp/yaml.h>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/offline/flight_feed.h"
#include "add_once.h"

namespace propulsion_estimator {
namespace gap {

MotorHealthReplay replayMotorHealth(const PropulsionModel& model, const Vehicle& vehicle, const FlightStreams& streams,
                                    const MotorHealthConfig& config) {
  OnboardSession session(model, vehicle, offline::replayOnboardConfig(vehicle, config));
  MotorHealthReplay replay;
  replay.first_flag_s = kNaN;
  double next_verdict_s = 0.0;
  const offline::FlightFeed feed(streams);
  for (const offline::Arrival& a : feed.arrivals()) {
    if (!feed.feed(a, &session)) continue;
    if (a.time_s < next_verdict_s) continue;
    next_verdict_s = a.time_s + 1.0;
    const MotorHealthVerdict verdict = session.motorHealth();
    replay.judgements += verdict.judged;
    if (verdict.flagged_channel == 0) continue;
    if (replay.flagged_channels.empty()) replay.first_flag_s = a.time_s;
    addOnce(&replay.flagged_channels, verdict.flagged_channel);
  }
  return replay;
}

std::string motorHealthReplayYaml(const std::vector<std::string>& names, const std::vector<MotorHealthReplay>& replays) {
  YAML::Emitter out;
  out << YAML::Comment("estimator_node's onboard motor-health check (~capability) replayed on each flight");
  out << YAML::BeginMap << YAML::Key << "flights" << YAML::Value << YAML::BeginSeq;
  for (std::size_t i = 0; i < replays.size(); ++i) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "bag" << YAML::Value << names[i] << YAML::Key << "judgements"
        << YAML::Value << replays[i].judgements << YAML::Key << "flagged" << YAML::Value << YAML::Flow
        << replays[i].flagged_channels << YAML::Key << "first_flag_s" << YAML::Value;
    if (std::isnan(replays[i].first_flag_s)) {
      out << YAML::Null;
    } else {
      out << replays[i].first_flag_s;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace gap
}  // namespace propulsion_estimator
