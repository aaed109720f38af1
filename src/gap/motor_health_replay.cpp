#include "propulsion_estimator/gap/motor_health_replay.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <numeric>

#include <yaml-cpp/yaml.h>

#include "propulsion_estimator/common/not_a_number.h"

namespace propulsion_estimator {
namespace gap {
namespace {

// Which stream a message comes from; at equal times the inputs sort before the RCOut message they feed.
enum class Stream { kBattery, kImu, kVerticalSpeed, kRcOut };

// The streams' messages in arrival order: stream and index in it.
struct Arrival {
  double time_s;
  Stream kind;
  std::size_t index;
};

std::vector<Arrival> arrivals(const FlightStreams& streams) {
  std::vector<Arrival> order;
  for (std::size_t i = 0; i < streams.battery.size(); ++i) order.push_back({streams.battery[i].time_s, Stream::kBattery, i});
  for (std::size_t i = 0; i < streams.imu.size(); ++i) order.push_back({streams.imu[i].time_s, Stream::kImu, i});
  for (std::size_t i = 0; i < streams.vertical_speed_m_s.size(); ++i) {
    order.push_back({streams.vertical_speed_m_s[i].time_s, Stream::kVerticalSpeed, i});
  }
  for (std::size_t i = 0; i < streams.rc_out.size(); ++i) order.push_back({streams.rc_out[i].time_s, Stream::kRcOut, i});
  std::stable_sort(order.begin(), order.end(), [](const Arrival& a, const Arrival& b) {
    return a.time_s < b.time_s || (a.time_s == b.time_s && a.kind < b.kind);
  });
  return order;
}

}  // namespace

MotorHealthReplay replayMotorHealth(const PropulsionModel& model, const Vehicle& vehicle, const FlightStreams& streams,
                                    const MotorHealthConfig& config) {
  EstimatorConfig estimator_config;
  estimator_config.motor_channels.resize(vehicle.rotors.size());
  std::iota(estimator_config.motor_channels.begin(), estimator_config.motor_channels.end(), 1);
  Estimator estimator(model, vehicle, estimator_config);
  MotorHealth health(vehicle, estimator_config.motor_channels, config);
  MotorHealthReplay replay;
  replay.first_flag_s = kNaN;
  double next_verdict_s = 0.0;
  std::vector<std::uint16_t> channels(vehicle.rotors.size());
  for (const Arrival& a : arrivals(streams)) {
    switch (a.kind) {
      case Stream::kBattery: estimator.addBattery(a.time_s, streams.battery[a.index].voltage_v); break;
      case Stream::kImu: {
        const ImuReading& imu = streams.imu[a.index];
        estimator.addImu(a.time_s, imu.orientation, imu.specific_force_m_s2);
        break;
      }
      case Stream::kVerticalSpeed: estimator.addVerticalSpeed(a.time_s, streams.vertical_speed_m_s[a.index].value); break;
      case Stream::kRcOut: {
        const RcOutFrame& frame = streams.rc_out[a.index];
        for (std::size_t k = 0; k < channels.size(); ++k) channels[k] = static_cast<std::uint16_t>(frame.pwm_us[k]);
        if (estimator.addMotorOutputs(a.time_s, a.time_s, channels.data(), channels.size()) != Rejection::kNone) break;
        health.add(estimator.output());
        if (a.time_s < next_verdict_s) break;
        next_verdict_s = a.time_s + 1.0;
        const MotorHealthVerdict verdict = health.verdict();
        replay.judgements += verdict.judged;
        if (verdict.flagged_channel == 0) break;
        if (replay.flagged_channels.empty()) replay.first_flag_s = a.time_s;
        if (std::find(replay.flagged_channels.begin(), replay.flagged_channels.end(), verdict.flagged_channel) ==
            replay.flagged_channels.end()) {
          replay.flagged_channels.push_back(verdict.flagged_channel);
        }
      }
    }
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
