#include "propulsion_estimator/logs/flight_streams.h"

#include <algorithm>

namespace propulsion_estimator {

const std::vector<std::string>& flightSignalNames() {
  static const std::vector<std::string> kNames = {"rc_out",          "battery",         "imu",
                                                  "pose",            "velocity",        "static_pressure",
                                                  "air_temperature", "rangefinder",     "motor_temperature",
                                                  "esc_telemetry",   "esc_status"};
  return kNames;
}

std::vector<std::size_t> signalCounts(const FlightStreams& streams) {
  const auto status = static_cast<std::size_t>(std::count_if(
      streams.esc.begin(), streams.esc.end(), [](const EscTelemetryReading& reading) { return reading.status; }));
  return {streams.rc_out.size(),
          streams.battery.size(),
          streams.imu.size(),
          streams.altitude_m.size(),
          streams.vertical_speed_m_s.size(),
          streams.static_pressure_pa.size(),
          streams.air_temperature_c.size(),
          streams.height_above_ground_m.size(),
          streams.motor_temperature_c.size(),
          streams.esc.size() - status,
          status};
}

}  // namespace propulsion_estimator
