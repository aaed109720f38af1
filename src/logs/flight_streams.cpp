#include "propulsion_estimator/logs/flight_streams.h"

namespace propulsion_estimator {

const std::vector<std::string>& flightSignalNames() {
  static const std::vector<std::string> kNames = {"rc_out",          "battery",         "imu",
                                                  "pose",            "velocity",        "static_pressure",
                                                  "air_temperature", "rangefinder",     "motor_temperature",
                                                  "esc_telemetry",   "esc_status"};
  return kNames;
}

std::vector<std::size_t> signalCounts(const FlightStreams& streams) {
  return {streams.rc_out.size(),
          streams.battery.size(),
          streams.imu.size(),
          streams.altitude_m.size(),
          streams.vertical_speed_m_s.size(),
          streams.static_pressure_pa.size(),
          streams.air_temperature_c.size(),
          streams.height_above_ground_m.size(),
          streams.motor_temperature_c.size(),
          streams.esc.size(),
          streams.esc.size()};
}

}  // namespace propulsion_estimator
