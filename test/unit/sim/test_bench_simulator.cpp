// The simulated thrust stand: its sensors' noise, the thesis' three experiments (chapter 4) and
// what it writes.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "propulsion_estimator/sim/stand/bench_simulator.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/logs/bench_csv.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

pe::sim::SimParams thesisParams() {
  return pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
}

struct RunRows {
  std::vector<double> voltage, thrust_g, current, rpm, pwm;
};

// Rows of run `run` (1-based) of a log.
RunRows rowsOfRun(const pe::BenchLog& log, int run) {
  RunRows rows;
  const std::vector<std::string>& runs = log.extra_columns.at("run");
  for (std::size_t i = 0; i < log.rows(); ++i) {
    if (runs[i] != std::to_string(run)) continue;
    rows.voltage.push_back(log.column(pe::BenchColumn::kVoltage)[i]);
    rows.thrust_g.push_back(log.column(pe::BenchColumn::kThrust)[i] / pe::kNewtonPerGramForce);
    rows.current.push_back(log.column(pe::BenchColumn::kCurrent)[i]);
    rows.rpm.push_back(log.column(pe::BenchColumn::kRpm)[i]);
    rows.pwm.push_back(log.column(pe::BenchColumn::kPwm)[i]);
  }
  return rows;
}

// Least-squares slope of y against x, as the thesis' linear fits of chapter 4.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  Eigen::MatrixXd a(x.size(), 2);
  Eigen::VectorXd b(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    a(i, 0) = x[i];
    a(i, 1) = 1.0;
    b(i) = y[i];
  }
  return a.colPivHouseholderQr().solve(b)(0);
}

std::string refusal(const pe::sim::BenchExperiment& experiment) {
  try {
    pe::sim::simulateBench(thesisParams(), {}, experiment, 1);
  } catch (const pe::InputError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(BenchSimulator, SensorNoiseMatchesTheConfiguredSigmas) {
  const pe::sim::SimParams params = thesisParams();
  const pe::sim::BenchExperiment sweep =
      pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  pe::BenchLog truth;
  const pe::BenchLog log = pe::sim::simulateBench(params, {}, sweep, 11, &truth);
  ASSERT_EQ(log.rows(), 8u * 141u);
  const pe::sim::BenchSensors& sensors = params.bench.sensors;
  const std::pair<pe::BenchColumn, const pe::sim::SensorNoise*> checks[] = {
      {pe::BenchColumn::kThrust, &sensors.thrust_n},         {pe::BenchColumn::kCurrent, &sensors.current_a},
      {pe::BenchColumn::kVoltage, &sensors.voltage_v},       {pe::BenchColumn::kRpm, &sensors.rpm},
      {pe::BenchColumn::kMotorTemp, &sensors.temperature_c}, {pe::BenchColumn::kAmbientTemp, &sensors.temperature_c}};
  for (const auto& [column, sensor] : checks) {
    double sum = 0.0, sum2 = 0.0;
    const std::size_t n = log.rows();
    for (std::size_t i = 0; i < n; ++i) {
      const double residual = log.column(column)[i] - truth.column(column)[i];
      sum += residual;
      sum2 += residual * residual;
    }
    const double mean = sum / n;
    const double sigma = std::sqrt(sum2 / n - mean * mean);
    // Gaussian noise plus quantisation: sqrt(sigma^2 + resolution^2 / 12); with 1128 readings the
    // sample deviation is within ~4 % of it (two standard errors), the mean within 4 sigma / sqrt(n).
    EXPECT_NEAR(sigma, sensor->effectiveSigma(), 0.06 * sensor->effectiveSigma()) << pe::benchColumnName(column);
    EXPECT_NEAR(mean, 0.0, 4.0 * sensor->effectiveSigma() / std::sqrt(n)) << pe::benchColumnName(column);
  }
  // The power column is what the thesis bench computed: measured voltage times measured current.
  for (std::size_t i = 0; i < log.rows(); ++i) {
    ASSERT_DOUBLE_EQ(log.column(pe::BenchColumn::kPower)[i],
                     log.column(pe::BenchColumn::kVoltage)[i] * log.column(pe::BenchColumn::kCurrent)[i]);
  }
}

TEST(BenchSimulator, MetadataDescribesTheRunAndItsNoise) {
  const pe::sim::SimParams params = thesisParams();
  pe::sim::BenchExperiment sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.voltages_v = {11.1};
  pe::sim::SimEffects effects;
  effects.supply_resistance_ohm = 0.02;
  const pe::BenchLog log = pe::sim::simulateBench(params, effects, sweep, 5);
  const auto& meta = log.metadata;
  EXPECT_EQ(meta.at("esc"), "DJI E300 Opto");
  EXPECT_EQ(meta.at("motor"), "DJI 2212 920KV");
  EXPECT_EQ(meta.at("propeller"), "DJI 9443");
  EXPECT_EQ(meta.at("supply"), "regulated");
  EXPECT_EQ(meta.at("experiment"), "pwm_sweep");
  EXPECT_EQ(meta.at("air_temperature_c"), "22");
  EXPECT_EQ(meta.at("air_pressure_pa"), "101325");
  EXPECT_EQ(meta.at("effects"), "supply_resistance(ohm=0.02)");
  EXPECT_EQ(meta.at("seed"), "5");
  EXPECT_EQ(meta.at("noise_sigma_thrust_n"), "0.0098");
  EXPECT_EQ(meta.at("noise_sigma_current_a"), "0.106");
  EXPECT_EQ(meta.at("resolution_current_a"), "0.074");
  EXPECT_EQ(meta.at("noise_sigma_voltage_v"), "0.012");
  EXPECT_EQ(meta.at("resolution_voltage_v"), "0.0244");
  EXPECT_EQ(meta.at("noise_sigma_rpm"), "10");
  EXPECT_EQ(meta.at("noise_sigma_temperature_c"), "0.05");
  const pe::sim::BenchExperiment discharge =
      pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kDischarge, params);
  pe::sim::BenchExperiment one = discharge;
  one.pwms_us = {1900.0};
  const pe::BenchLog on_battery = pe::sim::simulateBench(params, {}, one, 5);
  EXPECT_EQ(on_battery.metadata.at("supply"), "battery");
  EXPECT_EQ(on_battery.metadata.at("battery"), "Turnigy 3S 4000 mAh");
}

TEST(BenchSimulator, SweepsThePwmRangeAtEachVoltage) {
  const pe::sim::SimParams params = thesisParams();
  const pe::sim::BenchExperiment sweep =
      pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  pe::BenchLog truth;
  pe::sim::simulateBench(params, {}, sweep, 1, &truth);
  for (int run = 1; run <= 8; ++run) {
    const RunRows rows = rowsOfRun(truth, run);
    ASSERT_EQ(rows.pwm.size(), 141u);
    EXPECT_EQ(rows.pwm.front(), 1200.0);
    EXPECT_EQ(rows.pwm.back(), 1900.0);
    for (double v : rows.voltage) ASSERT_NEAR(v, 10.5 + 0.3 * (run - 1), 1e-12);
    for (std::size_t i = 1; i < rows.thrust_g.size(); ++i) ASSERT_GT(rows.thrust_g[i], rows.thrust_g[i - 1]);
  }
  const std::vector<double>& time = truth.column(pe::BenchColumn::kTime);
  EXPECT_DOUBLE_EQ(time.front(), 1.0);
  EXPECT_DOUBLE_EQ(time.back(), 8.0 * 141.0);
}

TEST(BenchSimulator, DischargeAtConstantPwmReproducesTheThesisSlopes) {
  // Thesis 4.2 at 1600 us, thrust, current and rpm against voltage: tables 4.6 (42.62 g/V),
  // 4.7 (0.3432 A/V), 4.10 (420.7 rpm/V).
  const pe::sim::SimParams params = thesisParams();
  const pe::sim::BenchExperiment discharge =
      pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kDischarge, params);
  ASSERT_EQ(discharge.pwms_us, (std::vector<double>{1600.0, 1700.0, 1800.0, 1900.0}));
  const pe::BenchLog log = pe::sim::simulateBench(params, {}, discharge, 2);
  const RunRows at_1600 = rowsOfRun(log, 1);
  EXPECT_NEAR(slope(at_1600.voltage, at_1600.thrust_g), 42.62, 0.10 * 42.62);
  EXPECT_NEAR(slope(at_1600.voltage, at_1600.current), 0.3432, 0.15 * 0.3432);
  EXPECT_NEAR(slope(at_1600.voltage, at_1600.rpm), 420.7, 0.10 * 420.7);
  // Each run goes from a full battery to the 10.5 V cut-off; the higher the PWM, the shorter.
  std::size_t previous = std::numeric_limits<std::size_t>::max();
  for (int run = 1; run <= 4; ++run) {
    const RunRows rows = rowsOfRun(log, run);
    EXPECT_GT(rows.voltage.front(), 12.4);
    for (double v : rows.voltage) ASSERT_GE(v, 10.5);
    EXPECT_LT(rows.voltage.back(), 10.6);
    EXPECT_LT(rows.voltage.size(), previous);
    previous = rows.voltage.size();
  }
}

TEST(BenchSimulator, ConstantThrustRunsHoldTheThrustAndReproduceTheThesisSlopes) {
  // Thesis 4.3 at 300 g: PWM against voltage -50.11 us/V (table 4.12), current -0.2325 A/V (4.13).
  const pe::sim::SimParams params = thesisParams();
  pe::sim::BenchExperiment held = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kConstantThrust, params);
  held.thrusts_n = {300.0 * pe::kNewtonPerGramForce, 500.0 * pe::kNewtonPerGramForce};
  const pe::BenchLog log = pe::sim::simulateBench(params, {}, held, 3);
  const RunRows at_300 = rowsOfRun(log, 1);
  double mean = 0.0;
  for (double t : at_300.thrust_g) mean += t / at_300.thrust_g.size();
  EXPECT_NEAR(mean, 300.0, 0.5);
  EXPECT_NEAR(slope(at_300.voltage, at_300.pwm), -50.11, 0.10 * 50.11);
  EXPECT_NEAR(slope(at_300.voltage, at_300.current), -0.2325, 0.15 * 0.2325);
  const RunRows at_500 = rowsOfRun(log, 2);
  mean = 0.0;
  for (double t : at_500.thrust_g) mean += t / at_500.thrust_g.size();
  EXPECT_NEAR(mean, 500.0, 0.5);
}

TEST(BenchSimulator, AppliesOnlyTheEffectsABenchShows) {
  const pe::sim::SimParams params = thesisParams();
  pe::sim::BenchExperiment sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.voltages_v = {12.0};
  pe::sim::SimEffects flight_only;
  flight_only.esc_offset_us = 30.0;
  flight_only.ground_effect_strength = 1.0;
  flight_only.thrust_loss_fraction = 0.1;
  flight_only.climb_inflow_strength = 1.0;
  const pe::BenchLog with = pe::sim::simulateBench(params, flight_only, sweep, 9);
  const pe::BenchLog without = pe::sim::simulateBench(params, {}, sweep, 9);
  EXPECT_EQ(with.column(pe::BenchColumn::kThrust), without.column(pe::BenchColumn::kThrust));
  EXPECT_EQ(with.metadata.at("effects"), "none");
  pe::sim::SimEffects mixed = flight_only;
  mixed.supply_resistance_ohm = 0.05;
  EXPECT_EQ(pe::sim::simulateBench(params, mixed, sweep, 9).metadata.at("effects"), "supply_resistance(ohm=0.05)");
}

TEST(BenchSimulator, TheSeedFixesTheNoise) {
  const pe::sim::SimParams params = thesisParams();
  pe::sim::BenchExperiment sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.voltages_v = {12.0};
  const pe::BenchLog a = pe::sim::simulateBench(params, {}, sweep, 21);
  const pe::BenchLog b = pe::sim::simulateBench(params, {}, sweep, 21);
  const pe::BenchLog c = pe::sim::simulateBench(params, {}, sweep, 22);
  EXPECT_EQ(a.column(pe::BenchColumn::kThrust), b.column(pe::BenchColumn::kThrust));
  EXPECT_NE(a.column(pe::BenchColumn::kThrust), c.column(pe::BenchColumn::kThrust));
}

TEST(BenchSimulator, WritesANativeBenchCsvThatReadsBack) {
  const pe::sim::SimParams params = thesisParams();
  pe::sim::BenchExperiment sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.voltages_v = {11.4, 12.6};
  const pe::BenchLog log = pe::sim::simulateBench(params, {}, sweep, 1);
  std::ostringstream out;
  pe::writeNativeBenchCsv(log, out);
  const std::string text = out.str();
  EXPECT_NE(text.find("# experiment: pwm_sweep\n"), std::string::npos);
  EXPECT_NE(text.find("\ntime_s,pwm_us,voltage_v,thrust_g,current_a,power_w,rpm,ambient_temp_c,motor_temp_c,run\n"),
            std::string::npos);
  // The log's line numbers are those of its rows in that file, and the reader gets the log back
  // (to the writer's 6 significant digits).
  const pe::BenchLog read = pe::parseNativeBenchCsv(text, "sim.csv");
  ASSERT_EQ(read.rows(), log.rows());
  EXPECT_EQ(read.line_numbers, log.line_numbers);
  EXPECT_EQ(read.metadata, log.metadata);
  EXPECT_EQ(read.extra_columns.at("run"), log.extra_columns.at("run"));
  for (int c = 0; c < pe::kBenchColumnCount; ++c) {
    const auto column = static_cast<pe::BenchColumn>(c);
    ASSERT_EQ(read.has(column), log.has(column)) << pe::benchColumnName(column);
    for (std::size_t i = 0; i < read.column(column).size(); ++i) {
      ASSERT_NEAR(read.column(column)[i], log.column(column)[i], 1e-5 * std::fabs(log.column(column)[i]) + 1e-12);
    }
  }
}

TEST(BenchSimulator, RefusesImpossibleExperiments) {
  const pe::sim::SimParams params = thesisParams();
  pe::sim::BenchExperiment sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.voltages_v.clear();
  EXPECT_EQ(refusal(sweep), "voltages_v: no supply voltage to sweep at");
  sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.pwm_step_us = 0.0;
  EXPECT_EQ(refusal(sweep), "pwm_step_us: must be a positive number, got 0");
  sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.pwm_start_us = 1900.0;
  sweep.pwm_end_us = 1200.0;
  EXPECT_EQ(refusal(sweep), "pwm_start_us: [1900, 1200] is not a range within 800..2200 us");
  // Counts of steps in double: a step of 1e-7 us is 7e9 pulse widths, not an overflowed int.
  sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.pwm_step_us = 1e-7;
  EXPECT_EQ(refusal(sweep), "pwm_step_us: 1e-07 gives 7000000001 pulse widths from 1200 to 1900 us (at most 1e+06)");
  sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.step_duration_s = 0.01;
  EXPECT_EQ(refusal(sweep), "step_duration_s: 0.01 is outside 0.02..3600 s");
  sweep.step_duration_s = 1e5;
  EXPECT_EQ(refusal(sweep), "step_duration_s: 100000 is outside 0.02..3600 s");
  pe::sim::BenchExperiment discharge = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kDischarge, params);
  discharge.sample_interval_s = 1e9;
  EXPECT_EQ(refusal(discharge), "sample_interval_s: 1e+09 is outside 0.02..3600 s");
  discharge = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kDischarge, params);
  discharge.pwms_us = {1800.0};
  discharge.cutoff_voltage_v = 9.0;  // below the empty pack's 9.81 V
  EXPECT_EQ(refusal(discharge),
            "discharge at 1800 us emptied the battery before the measured voltage fell below the 9 V cut-off");
}

TEST(BenchSimulator, RefusesAConstantThrustOutsideWhatThePwmRangeGives) {
  // From the full 3S pack (12.6 V behind 15 mOhm) the rotor gives 683 g at 1900 us (695 g at a
  // regulated 12.6 V) and 19 g at 1200 us; 3 load-cell sigmas (3 g) of slack either side. The
  // target is quoted as given, not as its round trip through newtons.
  const pe::sim::SimParams params = thesisParams();
  pe::sim::BenchExperiment held = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kConstantThrust, params);
  held.thrusts_n = {300.0 * pe::kNewtonPerGramForce, 2000.0 * pe::kNewtonPerGramForce};
  EXPECT_EQ(refusal(held), "constant thrust of 2000 g: only 683 g at 1900 us");
  held.thrusts_n = {10.0 * pe::kNewtonPerGramForce};
  EXPECT_EQ(refusal(held), "constant thrust of 10 g: already 19 g at 1200 us");
}
