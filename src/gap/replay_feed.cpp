#include "replay_feed.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace propulsion_estimator {
namespace gap {
namespace {

template <typename Reading>
void add(const std::vector<Reading>& stream, Stream kind, std::vector<Arrival>* order) {
  for (std::size_t i = 0; i < stream.size(); ++i) order->push_back({stream[i].time_s, kind, i});
}

}  // namespace

std::vector<Arrival> arrivals(const FlightStreams& streams) {
  std::vector<Arrival> order;
  order.reserve(streams.battery.size() + streams.imu.size() + streams.vertical_speed_m_s.size() +
                streams.horizontal_velocity.size() + streams.esc.size() + streams.rc_out.size());
  add(streams.battery, Stream::kBattery, &order);
  add(streams.imu, Stream::kImu, &order);
  add(streams.vertical_speed_m_s, Stream::kVerticalSpeed, &order);
  add(streams.horizontal_velocity, Stream::kHorizontalVelocity, &order);
  add(streams.esc, Stream::kEsc, &order);
  add(streams.rc_out, Stream::kRcOut, &order);
  std::stable_sort(order.begin(), order.end(), [](const Arrival& a, const Arrival& b) {
    return a.time_s < b.time_s || (a.time_s == b.time_s && a.kind < b.kind);
  });
  return order;
}

EstimatorConfig replayEstimatorConfig(const Vehicle& vehicle) {
  EstimatorConfig config;
  config.motor_channels.resize(vehicle.rotors.size());
  std::iota(config.motor_channels.begin(), config.motor_channels.end(), 1);
  return config;
}

bool feedEstimator(const FlightStreams& streams, const Arrival& arrival, Estimator* estimator) {
  const double t = arrival.time_s;
  switch (arrival.kind) {
    case Stream::kBattery: estimator->addBattery(t, streams.battery[arrival.index].voltage_v); return false;
    case Stream::kImu: {
      const ImuReading& imu = streams.imu[arrival.index];
      estimator->addImu(t, imu.orientation, imu.specific_force_m_s2);
      return false;
    }
    case Stream::kVerticalSpeed: estimator->addVerticalSpeed(t, streams.vertical_speed_m_s[arrival.index].value); return false;
    case Stream::kHorizontalVelocity: {
      const HorizontalVelocityReading& velocity = streams.horizontal_velocity[arrival.index];
      estimator->addHorizontalVelocity(t, velocity.east_m_s, velocity.north_m_s);
      return false;
    }
    case Stream::kEsc: return false;
    case Stream::kRcOut: {
      const RcOutFrame& frame = streams.rc_out[arrival.index];
      // The estimator's channels (the vehicle's rotors), as the flight logged them.
      const std::size_t motors = std::min<std::size_t>(estimator->config().motor_channels.size(), kMaxMotors);
      std::array<std::uint16_t, kMaxMotors> channels{};
      for (std::size_t k = 0; k < motors; ++k) channels[k] = static_cast<std::uint16_t>(frame.pwm_us[k]);
      return estimator->addMotorOutputs(t, t, channels.data(), motors) == Rejection::kNone;
    }
  }
  return false;
}

}  // namespace gap
}  // namespace propulsion_estimator
