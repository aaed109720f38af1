// Time to simulate the default three-minute flight (config/sim/default_flight.yaml, rc/out at
// 50 Hz, 2 ms physics step): the core simulation with every reading built and discarded, and the
// same writing a bag (uncompressed, and bz2 as the bundled demo) to a temporary file.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "propulsion_estimator/bag/bag_flight_sink.h"

namespace pe = propulsion_estimator;

namespace {

struct Inputs {
  pe::sim::SimParams params =
      pe::sim::loadSimParamsFile(std::string(PE_REPO_DIR) + "/config/sim/e300_dji2212_dji9443.yaml");
  pe::sim::FlightProfile profile =
      pe::sim::loadFlightProfileFile(std::string(PE_REPO_DIR) + "/config/sim/default_flight.yaml");
  pe::Vehicle vehicle = pe::loadVehicleUrdf(profile.vehicle.urdf_path);
};

const Inputs& inputs() {
  static const Inputs loaded;
  return loaded;
}

// Receives every reading and keeps nothing.
struct DiscardingSink : pe::sim::FlightSink {
  std::size_t messages = 0;
  void rcOut(const pe::sim::RcOutSample&) override { ++messages; }
  void battery(const pe::sim::BatterySample&) override { ++messages; }
  void imu(const pe::sim::ImuSample&) override { ++messages; }
  void pose(const pe::sim::PoseSample&) override { ++messages; }
  void velocity(const pe::sim::VelocitySample&) override { ++messages; }
  void staticPressure(const pe::sim::ScalarSample&) override { ++messages; }
  void airTemperature(const pe::sim::ScalarSample&) override { ++messages; }
  void rangefinder(const pe::sim::RangeSample&) override { ++messages; }
  void motorTemperature(const pe::sim::ScalarSample&) override { ++messages; }
  void truth(const pe::sim::TruthSample&) override { ++messages; }
};

void BM_FlightCore(benchmark::State& state) {
  const Inputs& in = inputs();
  double simulated_s = 0.0;
  for (auto _ : state) {
    DiscardingSink sink;
    simulated_s = pe::sim::simulateFlight(in.params, {}, in.profile, in.vehicle, 1, &sink).duration_s;
    benchmark::DoNotOptimize(sink.messages);
  }
  state.counters["simulated_s"] = simulated_s;
}
BENCHMARK(BM_FlightCore)->Unit(benchmark::kMillisecond);

void BM_FlightToBag(benchmark::State& state) {
  const Inputs& in = inputs();
  const auto compression = static_cast<rosbag::compression::CompressionType>(state.range(0));
  const std::string path =
      (std::filesystem::temp_directory_path() / ("bench_simulate_" + std::to_string(::getpid()) + ".bag")).string();
  for (auto _ : state) {
    pe::BagFlightSink sink(path, compression);
    pe::sim::simulateFlight(in.params, {}, in.profile, in.vehicle, 1, &sink);
    sink.close();
  }
  state.counters["bag_mb"] = std::filesystem::file_size(path) / 1e6;
  std::filesystem::remove(path);
}
BENCHMARK(BM_FlightToBag)
    ->Arg(rosbag::compression::Uncompressed)
    ->Arg(rosbag::compression::BZ2)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
