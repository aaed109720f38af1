#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "propulsion_estimator/logs/bench_log.h"
#include "propulsion_estimator/sim/stand/bench_simulator.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/common/units.h"
#include "test_paths.h"

// Constant-voltage PWM sweeps like thesis 4.1 (1200..1900 us in 5 us steps at 8 supply voltages,
// 10.5..12.6 V): simulatedSweeps() from the physics simulator (`simulate bench`), and
// syntheticSweeps() from a known smooth chain whose noise-free values the tests can compare with.
struct SweepSet {
  std::vector<propulsion_estimator::BenchLog> logs;  // one per voltage level
  // Standard deviation of the noise added to each measured quantity, in the fit's units.
  double thrust_sigma_g = 0.0;
  double current_sigma_a = 0.0;
  double power_sigma_w = 0.0;
  double rpm_sigma = 0.0;
};

// The noise-free chain: a motor whose speed rises with duty and supply voltage, slowed by its
// load, and a propeller with thrust ~ rpm^2 and shaft power ~ rpm^3 (degree 6 in PWM: no
// polynomial of the candidate set reproduces power exactly). Tuned near the thesis' E300-2212-9443
// (8.7k rpm, 680 g, 110 W at 12.6 V and 1900 us).
struct SmoothChain {
  static double duty(double pwm_us) { return (pwm_us - 1100.0) / 800.0; }
  static double rpm(double pwm_us, double voltage_v) {
    const double d = duty(pwm_us);
    return 920.0 * voltage_v * d * (0.85 - 0.1 * d);
  }
  static double thrustGrams(double pwm_us, double voltage_v) { return 9.0e-6 * std::pow(rpm(pwm_us, voltage_v), 2); }
  static double powerWatts(double pwm_us, double voltage_v) {
    return 1.6e-10 * std::pow(rpm(pwm_us, voltage_v), 3) + 0.5 * voltage_v;
  }
  static double currentAmps(double pwm_us, double voltage_v) { return powerWatts(pwm_us, voltage_v) / voltage_v; }
};

inline SweepSet syntheticSweeps(unsigned seed = 42) {
  namespace pe = propulsion_estimator;
  SweepSet set;
  set.thrust_sigma_g = 4.0;
  set.current_sigma_a = 0.05;
  set.power_sigma_w = 0.5;
  set.rpm_sigma = 30.0;
  const double voltage_sigma_v = 0.01;
  std::mt19937 random(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  for (int level = 0; level < 8; ++level) {
    const double voltage = 10.5 + 0.3 * level;
    pe::BenchLog log;
    log.source = "sweep_" + std::to_string(level) + ".csv";
    log.metadata = {{"esc", "synthetic ESC"},   {"motor", "synthetic 920KV"}, {"propeller", "synthetic 9443"},
                    {"supply", "regulated"},    {"air_temperature_c", "22"},  {"air_pressure_pa", "101325"},
                    {"experiment", "pwm_sweep"}};
    int line = 8;
    for (double pwm = 1200.0; pwm <= 1900.0; pwm += 5.0) {
      log.column(pe::BenchColumn::kTime).push_back(0.5 * (line - 8));
      log.column(pe::BenchColumn::kPwm).push_back(pwm);
      log.column(pe::BenchColumn::kVoltage).push_back(voltage + voltage_sigma_v * unit(random));
      log.column(pe::BenchColumn::kThrust)
          .push_back((SmoothChain::thrustGrams(pwm, voltage) + set.thrust_sigma_g * unit(random)) *
                     pe::kNewtonPerGramForce);
      log.column(pe::BenchColumn::kCurrent)
          .push_back(SmoothChain::currentAmps(pwm, voltage) + set.current_sigma_a * unit(random));
      log.column(pe::BenchColumn::kPower)
          .push_back(SmoothChain::powerWatts(pwm, voltage) + set.power_sigma_w * unit(random));
      log.column(pe::BenchColumn::kRpm).push_back(SmoothChain::rpm(pwm, voltage) + set.rpm_sigma * unit(random));
      log.line_numbers.push_back(line++);
    }
    set.logs.push_back(std::move(log));
  }
  return set;
}

// The simulator's thesis sweep of the E300-2212-9443 (8 voltages, 1200..1900 us every 5 us), one
// log per voltage as a bench writes one file per sweep. The noise of each quantity is what the
// simulated sensors added: the RMS of logged minus noise-free values (quantization included;
// power is measured voltage times measured current, as on the thesis bench).
inline SweepSet simulatedSweeps(unsigned seed = 3) {
  namespace pe = propulsion_estimator;
  const pe::sim::SimParams params = pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
  pe::BenchLog truth;
  const pe::BenchLog logged = pe::sim::simulateBench(
      params, pe::sim::SimEffects{}, pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params),
      seed, &truth);
  const std::vector<std::string>& run = logged.extra_columns.at("run");
  SweepSet set;
  auto rms = [&](pe::BenchColumn column, double scale) {
    double sum = 0.0;
    for (std::size_t r = 0; r < logged.rows(); ++r) {
      sum += std::pow((logged.column(column)[r] - truth.column(column)[r]) * scale, 2);
    }
    return std::sqrt(sum / static_cast<double>(logged.rows()));
  };
  set.thrust_sigma_g = rms(pe::BenchColumn::kThrust, 1.0 / pe::kNewtonPerGramForce);
  set.current_sigma_a = rms(pe::BenchColumn::kCurrent, 1.0);
  set.power_sigma_w = rms(pe::BenchColumn::kPower, 1.0);
  set.rpm_sigma = rms(pe::BenchColumn::kRpm, 1.0);
  for (std::size_t r = 0; r < logged.rows(); ++r) {
    if (r == 0 || run[r] != run[r - 1]) {
      set.logs.emplace_back();
      set.logs.back().source = "simulated_sweep_" + run[r] + ".csv";
      set.logs.back().metadata = logged.metadata;
    }
    pe::BenchLog& log = set.logs.back();
    for (int c = 0; c < pe::kBenchColumnCount; ++c) {
      if (!logged.columns[c].empty()) log.columns[c].push_back(logged.columns[c][r]);
    }
    log.line_numbers.push_back(logged.line_numbers[r]);
  }
  return set;
}
