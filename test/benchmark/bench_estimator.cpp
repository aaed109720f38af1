// Per-message cost of the onboard estimation: model evaluation and the whole core pipeline for one
// RCOut message, and loading the model file. ROS-free, so that make arm64 cross-builds it too;
// decoding the RCOut ShapeShifter in the ROS layer is measured by bench_rcout_decode.cpp.
#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/model/model_yaml.h"

namespace pe = propulsion_estimator;

namespace {

pe::PropulsionModel thesisModel() { return pe::loadModelFile(std::string(PE_REPO_DIR) + "/config/e300_dji2212_dji9443.yaml"); }

// What the node does once at start-up: reading, checking and building the model from its YAML file.
void BM_LoadModel(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(thesisModel());
}
BENCHMARK(BM_LoadModel)->Unit(benchmark::kMicrosecond);

void BM_ModelEvaluate(benchmark::State& state) {
  const pe::PropulsionModel model = thesisModel();
  pe::OperatingPoint point;
  double pwm = 1200.0;
  for (auto _ : state) {
    pwm = pwm >= 1900.0 ? 1200.0 : pwm + 0.7;
    model.evaluate(pwm, 11.4, &point);
    benchmark::DoNotOptimize(point);
  }
}
BENCHMARK(BM_ModelEvaluate);

// All five outputs of every motor of a message, as the estimator evaluates them (one motor per
// surface evaluation, the PWMs of a hover differing a little).
void BM_ModelEvaluateMotors(benchmark::State& state) {
  const pe::PropulsionModel model = thesisModel();
  std::vector<pe::OperatingPoint> points(static_cast<std::size_t>(state.range(0)));
  double pwm = 1600.0;
  for (auto _ : state) {
    pwm = pwm >= 1700.0 ? 1600.0 : pwm + 0.7;
    for (std::size_t i = 0; i < points.size(); ++i) model.evaluate(pwm + static_cast<double>(i), 11.4, &points[i]);
    benchmark::DoNotOptimize(points.data());
  }
}
BENCHMARK(BM_ModelEvaluateMotors)->Arg(8);

void BM_EstimatorRcOutMessage(benchmark::State& state) {
  const int motors = static_cast<int>(state.range(0));
  pe::EstimatorConfig config;
  config.motor_channels.clear();
  for (int k = 1; k <= motors; ++k) config.motor_channels.push_back(k);
  pe::Estimator estimator(thesisModel(), pe::Vehicle::upwardRotors(motors), config);
  std::vector<std::uint16_t> channels(16, 1690);
  double t = 0.0;
  for (auto _ : state) {
    t += 0.02;
    if (static_cast<int>(t * 50.0) % 50 == 0) estimator.addBattery(t, 11.4);
    estimator.addImu(t, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.0, 0.0, 9.81));
    channels[0] = static_cast<std::uint16_t>(1680 + static_cast<int>(t * 50.0) % 20);
    benchmark::DoNotOptimize(estimator.addMotorOutputs(t, t, channels.data(), channels.size()));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EstimatorRcOutMessage)->Arg(4)->Arg(6)->Arg(8);

}  // namespace

BENCHMARK_MAIN();
