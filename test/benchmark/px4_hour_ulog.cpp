// Writes an hour of PX4 ULog for make bench: two simulated 30-minute flights (the hovers, climbs
// and descents of scripts/bench_diagnose_gap.sh), each with its manifest, logged at PX4's default
// logging rates or faster (logged_topics.cpp: actuator_outputs 100 ms, vehicle_local_position
// 100 ms, vehicle_air_data 200 ms, battery_status 200 ms; sensor_combined at the IMU's rate, here
// 200 Hz, and vehicle_attitude with it, faster than its default 50 ms).
//   px4_hour_ulog PARAMS PROFILE OUT_DIR
#include <cstdio>
#include <exception>
#include <string>

#include "propulsion_estimator/logs/flight_manifest.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/flight/ulog_flight_sink.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"

namespace pe = propulsion_estimator;

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: px4_hour_ulog PARAMS PROFILE OUT_DIR\n");
    return 2;
  }
  try {
    const pe::sim::SimParams params = pe::sim::loadSimParamsFile(argv[1]);
    const pe::sim::FlightProfile profile = pe::sim::loadFlightProfileFile(argv[2]);
    const pe::Vehicle vehicle = pe::loadVehicleUrdf(profile.vehicle.urdf_path);
    pe::sim::FlightSensorParams sensors;
    sensors.imu_rate_hz = 200.0;
    sensors.pose_rate_hz = 10.0;
    sensors.pressure_rate_hz = 5.0;
    sensors.battery_rate_hz = 5.0;
    pe::FlightManifest manifest;
    for (int seed = 1; seed <= 2; ++seed) {
      pe::sim::UlogFlightSink sink(pe::sim::UlogLayout::kPx4v1_12, profile.autopilot.pwm_min_us,
                                   profile.autopilot.pwm_max_us);
      const pe::sim::FlightResult result = pe::sim::simulateFlight(params, {}, profile, vehicle, seed, &sink, sensors);
      const std::string name = "flight_" + std::to_string(seed) + ".ulg";
      sink.save(std::string(argv[3]) + "/" + name);
      manifest.flights.push_back({name, result.segments, {}});
      std::printf("%s: %.0f s, %zu bytes\n", name.c_str(), result.duration_s, sink.bytes().size());
    }
    pe::saveFlightManifest(manifest, std::string(argv[3]) + "/flights.yaml", "An hour of PX4 ULog for make bench");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "px4_hour_ulog: %s\n", e.what());
    return 1;
  }
  return 0;
}
