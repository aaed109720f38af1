#pragma once

#include <cstddef>
#include <vector>

#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/logs/flight_streams.h"
#include "propulsion_estimator/model/propulsion_model.h"
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
  kStaticPressure,
  kAirTemperature,
  kRange,
  kMotorTemperature,
  kEsc,
  kRcOut,
};

/// One logged message: its time (s on the log's clock), stream and index in that stream.
struct Arrival {
  double time_s;      ///< s on the log's clock
  Stream kind;        ///< the stream
  std::size_t index;  ///< in that stream
};

/// The estimator's configuration for a logged flight: the node's defaults
/// (config/estimator_params.yaml), the vehicle's rotors on channels 1..n.
EstimatorConfig replayEstimatorConfig(const Vehicle& vehicle);

/// A logged flight's messages in the order a replayed bag hands them to the node, and what the
/// node takes from each: the battery's voltage, the IMU, the velocity, the static pressure and
/// RCOut always; the battery current, the air temperature, the rangefinder (a logged range is a
/// valid one) and the motor temperature only where the model has an effect that reads them, as
/// the node subscribes. ESC telemetry is left to the caller (the live model check).
class FlightFeed {
 public:
  /// Sorts every message of `streams` by time (allocates once); `streams` must outlive the feed.
  FlightFeed(const FlightStreams& streams, const PropulsionModel& model);

  /// Every message, by time; at equal times the inputs before the RCOut message they feed.
  const std::vector<Arrival>& arrivals() const { return arrivals_; }
  /// Gives `estimator` the message `arrival`, received at its log time, as the node's callbacks
  /// do. True when it was an RCOut message the estimator accepted, whose output() the onboard
  /// checks then take.
  bool feed(const Arrival& arrival, Estimator* estimator) const;

 private:
  const FlightStreams& streams_;
  std::vector<Arrival> arrivals_;
  bool battery_current_ = false;
  bool air_temperature_ = false;
  bool range_ = false;
  bool motor_temperature_ = false;
};

}  // namespace offline
}  // namespace propulsion_estimator
