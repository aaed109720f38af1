#include "propulsion_estimator/offline/flight_feed.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>

#include "propulsion_estimator/common/not_a_number.h"

namespace propulsion_estimator {
namespace offline {
namespace {

bool before(const Arrival& a, const Arrival& b) { return a.time_s < b.time_s || (a.time_s == b.time_s && a.kind < b.kind); }

// Appends a stream's messages and merges them with those before: each stream comes in time order
// (sorted first where a log's is not), so a merge per stream orders a long log in a fraction of a sort.
template <typename Reading>
void add(const std::vector<Reading>& stream, Stream kind, std::vector<Arrival>* order,
         input::Scalar scalar = input::Scalar::kStaticPressure) {
  const std::ptrdiff_t middle = static_cast<std::ptrdiff_t>(order->size());
  for (std::size_t i = 0; i < stream.size(); ++i) order->push_back({stream[i].time_s, kind, i, scalar});
  if (!std::is_sorted(order->begin() + middle, order->end(), before)) {
    std::stable_sort(order->begin() + middle, order->end(), before);
  }
  std::inplace_merge(order->begin(), order->begin() + middle, order->end(), before);
}

Rejection feedRcOut(const RcOutFrame& frame, double t, OnboardSession* session) {
  // The estimator's channels (the vehicle's rotors), as the flight logged them.
  const std::size_t motors = std::min<std::size_t>(session->config().estimator.motor_channels.size(), kMaxMotors);
  std::array<std::uint16_t, kMaxMotors> channels{};
  for (std::size_t k = 0; k < motors; ++k) channels[k] = static_cast<std::uint16_t>(frame.pwm_us[k]);
  return session->addMotorOutputs(t, t, channels.data(), motors);
}

// The logged reading as MAVROS delivers it: ESC i on channel i + 1.
EscTelemetry escMessage(const EscTelemetryReading& reading) {
  EscTelemetry out;
  out.stamp_s = reading.time_s;
  for (int k = 0; k < reading.escs; ++k) {
    out.escs.push_back({reading.time_s, reading.rpm[k], reading.current_a[k], reading.voltage_v[k], kNaN,
                        reading.count[k]});
  }
  return out;
}

}  // namespace

EstimatorConfig replayEstimatorConfig(const Vehicle& vehicle) {
  EstimatorConfig config;
  config.motor_channels.resize(vehicle.rotors.size());
  std::iota(config.motor_channels.begin(), config.motor_channels.end(), 1);
  return config;
}

OnboardConfig replayOnboardConfig(const Vehicle& vehicle, const MotorHealthConfig& motor_health,
                                  const ModelCheckConfig& esc_telemetry) {
  OnboardConfig config;
  config.estimator = replayEstimatorConfig(vehicle);
  config.capability.motor_health = motor_health;
  config.esc_telemetry = esc_telemetry;
  return config;
}

FlightFeed::FlightFeed(const FlightStreams& streams) : streams_(streams) {
  std::size_t inputs = 0;
  for (const auto& readings : streams.inputs) inputs += readings.size();
  arrivals_.reserve(streams.battery.size() + streams.imu.size() + streams.vertical_speed_m_s.size() +
                    streams.horizontal_velocity.size() + inputs + streams.esc.size() + streams.rc_out.size());
  add(streams.battery, Stream::kBattery, &arrivals_);
  add(streams.imu, Stream::kImu, &arrivals_);
  add(streams.vertical_speed_m_s, Stream::kVerticalSpeed, &arrivals_);
  add(streams.horizontal_velocity, Stream::kHorizontalVelocity, &arrivals_);
  for (input::Scalar scalar : input::kAllScalars) add(streams.input(scalar), Stream::kInput, &arrivals_, scalar);
  add(streams.esc, Stream::kEsc, &arrivals_);
  add(streams.rc_out, Stream::kRcOut, &arrivals_);
}

bool FlightFeed::feed(const Arrival& arrival, OnboardSession* session) const {
  const double t = arrival.time_s;
  const std::size_t i = arrival.index;
  switch (arrival.kind) {
    case Stream::kBattery: {
      const BatteryReading& b = streams_.battery[i];
      session->addBattery(t, b.voltage_v, b.current_a, kNaN);
      return false;
    }
    case Stream::kImu:
      session->addImu(t, streams_.imu[i].orientation, streams_.imu[i].specific_force_m_s2);
      return false;
    case Stream::kVerticalSpeed: session->addVerticalSpeed(t, streams_.vertical_speed_m_s[i].value); return false;
    case Stream::kHorizontalVelocity:
      session->addHorizontalVelocity(t, streams_.horizontal_velocity[i].east_m_s,
                                     streams_.horizontal_velocity[i].north_m_s);
      return false;
    case Stream::kInput: session->addInput(arrival.input, t, streams_.input(arrival.input)[i].value); return false;
    case Stream::kEsc: session->addEscTelemetry(t, escMessage(streams_.esc[i])); return false;
    case Stream::kRcOut: return feedRcOut(streams_.rc_out[i], t, session) == Rejection::kNone;
  }
  return false;
}

}  // namespace offline
}  // namespace propulsion_estimator
