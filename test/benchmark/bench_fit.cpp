// fit_surfaces' core on a million bench rows: reading the rows into per-group Gram matrices once,
// then choosing the degrees of every output by grouped cross-validation on those matrices.
#include "propulsion_estimator/fitting/surface_fit.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "propulsion_estimator/common/units.h"

namespace pe = propulsion_estimator;

namespace {

// Continuously logged PWM ramps at 8 supply voltages (thesis 4.1 at a high sample rate), from a
// smooth motor-propeller chain with sensor noise; `rows` in total.
std::vector<pe::BenchLog> rampLogs(int rows) {
  std::mt19937 random(1);
  std::uniform_real_distribution<double> pwm(1200.0, 1900.0);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<pe::BenchLog> logs(8);
  for (int level = 0; level < 8; ++level) {
    pe::BenchLog& log = logs[level];
    const double voltage = 10.5 + 0.3 * level;
    log.source = "ramp_" + std::to_string(level) + ".csv";
    log.metadata = {{"esc", "E"},
                    {"motor", "M"},
                    {"propeller", "P"},
                    {"supply", "regulated"},
                    {"air_temperature_c", "22"},
                    {"air_pressure_pa", "101325"}};
    const int n = rows / 8;
    for (auto* column : {&log.column(pe::BenchColumn::kPwm), &log.column(pe::BenchColumn::kVoltage),
                         &log.column(pe::BenchColumn::kThrust), &log.column(pe::BenchColumn::kCurrent),
                         &log.column(pe::BenchColumn::kPower), &log.column(pe::BenchColumn::kRpm)}) {
      column->reserve(n);
    }
    for (int k = 0; k < n; ++k) {
      const double x = pwm(random);
      const double d = (x - 1100.0) / 800.0;
      const double rpm = 920.0 * voltage * d * (0.85 - 0.1 * d);
      const double power = 1.6e-10 * rpm * rpm * rpm + 0.5 * voltage;
      log.column(pe::BenchColumn::kPwm).push_back(x);
      log.column(pe::BenchColumn::kVoltage).push_back(voltage + 0.01 * noise(random));
      log.column(pe::BenchColumn::kThrust)
          .push_back((9.0e-6 * rpm * rpm + 4.0 * noise(random)) * pe::kNewtonPerGramForce);
      log.column(pe::BenchColumn::kCurrent).push_back(power / voltage + 0.05 * noise(random));
      log.column(pe::BenchColumn::kPower).push_back(power + 0.5 * noise(random));
      log.column(pe::BenchColumn::kRpm).push_back(rpm + 30.0 * noise(random));
      log.line_numbers.push_back(k + 8);
    }
  }
  return logs;
}

void BM_FitMillionRows(benchmark::State& state) {
  const std::vector<pe::BenchLog> logs = rampLogs(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(logs, {});
    benchmark::DoNotOptimize(fit);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_FitMillionRows)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
