#include "propulsion_estimator/logs/flight_streams.h"

#include <algorithm>

namespace propulsion_estimator {

const std::vector<std::string>& flightSignalNames() {
  static const std::vector<std::string> kNames = [] {
    std::vector<std::string> names = {"rc_out", "battery", "imu", "pose", "velocity"};
    for (input::Scalar scalar : input::kAllScalars) names.push_back(input::spec(scalar).name);
    names.insert(names.end(), {"esc_telemetry", "esc_status"});
    return names;
  }();
  return kNames;
}

std::vector<std::size_t> signalCounts(const FlightStreams& streams) {
  const auto status = static_cast<std::size_t>(std::count_if(
      streams.esc.begin(), streams.esc.end(), [](const EscTelemetryReading& reading) { return reading.status; }));
  std::vector<std::size_t> counts = {streams.rc_out.size(), streams.battery.size(), streams.imu.size(),
                                     streams.altitude_m.size(), streams.vertical_speed_m_s.size()};
  for (const auto& readings : streams.inputs) counts.push_back(readings.size());
  counts.insert(counts.end(), {streams.esc.size() - status, status});
  return counts;
}

}  // namespace propulsion_estimator
