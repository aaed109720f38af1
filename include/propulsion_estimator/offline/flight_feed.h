#pragma once

#include <cstddef>
#include <vector>

#include "propulsion_estimator/logs/flight_streams.h"
#include "propulsion_estimator/onboard/onboard_session.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace offline {

/// Which stream a logged message comes from; at equal times the inputs sort before the RCOut
/// message they feed.
enum class Stream {
  kBattery,
  kImu,
  kVerticalSpeed,
  kHorizontalVelocity,
  kInput,  ///< a scalar input: Arrival::input says which
  kEsc,
  kRcOut,
};

/// One logged message: its time (s on the log's clock), stream and index in that stream.
struct Arrival {
  double time_s;      ///< s on the log's clock
  Stream kind;        ///< the stream
  std::size_t index;  ///< in that stream
  input::Scalar input = input::Scalar::kStaticPressure;  ///< for Stream::kInput
};

/// The estimator's configuration for a logged flight: the node's defaults
/// (config/estimator_params.yaml), the vehicle's rotors on channels 1..n.
EstimatorConfig replayEstimatorConfig(const Vehicle& vehicle);

/// A logged flight's messages in the order a replayed bag hands them to the node, each handed to
/// the onboard session as the node's callbacks do: every signal the log carries (the session
/// drops those the model's effects do not read, as the node does not subscribe to them), the ESC
/// telemetry as MAVROS delivers it (ESC i on channel i + 1), a logged range as a valid one.
class FlightFeed {
 public:
  /// Sorts every message of `streams` by time (allocates once); `streams` must outlive the feed.
  explicit FlightFeed(const FlightStreams& streams);

  /// Every message, by time; at equal times the inputs before the RCOut message they feed.
  const std::vector<Arrival>& arrivals() const { return arrivals_; }
  /// Gives `session` the message `arrival`, received at its log time. True when it was an RCOut
  /// message the estimator accepted.
  bool feed(const Arrival& arrival, OnboardSession* session) const;

 private:
  const FlightStreams& streams_;
  std::vector<Arrival> arrivals_;
};

/// The onboard session's configuration for a logged flight: replayEstimatorConfig, the node's
/// defaults for the rest, `motor_health` and `esc_telemetry` as given.
OnboardConfig replayOnboardConfig(const Vehicle& vehicle, const MotorHealthConfig& motor_health = {},
                                  const ModelCheckConfig& esc_telemetry = {});

}  // namespace offline
}  // namespace propulsion_estimator
