// A logged flight's messages in the order the node would have received them (private to src/gap/):
// the replays of the node's onboard checks feed the core estimator in this order.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/logs/flight_streams.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace gap {

// Which stream a message comes from; at equal times the inputs sort before the RCOut message they feed.
enum class Stream { kBattery, kImu, kVerticalSpeed, kHorizontalVelocity, kEsc, kRcOut };

// One message: its time, stream and index in that stream.
struct Arrival {
  double time_s;
  Stream kind;
  std::size_t index;
};

// Every message of `streams`' battery, IMU, vertical speed, horizontal velocity, ESC telemetry and
// RCOut, by time.
std::vector<Arrival> arrivals(const FlightStreams& streams);

// The estimator's configuration in a replay: the defaults, the vehicle's rotors on channels 1..n.
EstimatorConfig replayEstimatorConfig(const Vehicle& vehicle);

// Gives `estimator` the battery, IMU, velocity or RCOut message `arrival` as the node does
// (received at its log time); true when it was an RCOut message the estimator accepted, whose
// output the checks then take. ESC telemetry is left to the caller.
bool feedEstimator(const FlightStreams& streams, const Arrival& arrival, Estimator* estimator);

// Appends `value` to `list` unless it is there already (a replay's flagged channels and verdicts).
template <typename T>
void addOnce(std::vector<T>* list, const T& value) {
  if (std::find(list->begin(), list->end(), value) == list->end()) list->push_back(value);
}

}  // namespace gap
}  // namespace propulsion_estimator
