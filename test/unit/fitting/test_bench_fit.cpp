#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <string>

#include "bench_sweep_fixture.h"
#include "propulsion_estimator/fitting/surface_fit.h"
#include "propulsion_estimator/logs/bench_log_reader.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/fitting/fit_report.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/common/units.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

const std::string kStrawson = "test/data/strawson_motor_propeller/";

// Bench conditions the Strawson exports do not carry (the stand software writes no metadata).
pe::fitting::FitOptions strawsonOptions(const std::string& motor, const std::string& propeller) {
  pe::fitting::FitOptions options;
  options.esc = "unknown BLHeli ESC";
  options.motor = motor;
  options.propeller = propeller;
  options.air_temperature_c = 20.0;
  options.air_pressure_pa = 101325.0;
  options.supply = pe::SupplyKind::kRegulated;
  return options;
}

std::vector<pe::BenchLog> strawsonPair(const std::string& combination) {
  return {pe::readBenchLog(repoPath(kStrawson + combination + "_7.csv")),
          pe::readBenchLog(repoPath(kStrawson + combination + "_11.csv"))};
}

double rmseOn(const pe::PropulsionModel& model, pe::Output output, const pe::BenchLog& log) {
  double sse = 0.0;
  for (std::size_t r = 0; r < log.rows(); ++r) {
    const double x = log.column(pe::BenchColumn::kPwm)[r];
    const double v = log.column(pe::BenchColumn::kVoltage)[r];
    double measured = 0.0;
    switch (output) {
      case pe::Output::kThrust:
        measured = log.column(pe::BenchColumn::kThrust)[r] / pe::kNewtonPerGramForce;
        break;
      case pe::Output::kCurrent:
        measured = log.column(pe::BenchColumn::kCurrent)[r];
        break;
      case pe::Output::kPower:
        measured = log.column(pe::BenchColumn::kPower)[r];
        break;
      default:
        measured = log.column(pe::BenchColumn::kRpm)[r];
        break;
    }
    const double error = model.evaluateRaw(output, x, v) - measured;
    sse += error * error;
  }
  return std::sqrt(sse / static_cast<double>(log.rows()));
}

std::string refusal(const std::vector<pe::BenchLog>& logs, const pe::fitting::FitOptions& options = {}) {
  try {
    pe::fitting::fitBenchModel(logs, options);
  } catch (const pe::InputError& e) {
    return e.what();
  }
  return "accepted";
}

// A clean native-style log: thrust_g = f(pwm, voltage) on a grid, no noise.
pe::BenchLog gridLog(const std::string& name, const std::vector<double>& pwms, double voltage,
                     double (*thrust_g)(double, double)) {
  pe::BenchLog log;
  log.source = name;
  log.metadata = {{"esc", "E"},
                  {"motor", "M"},
                  {"propeller", "P"},
                  {"supply", "battery"},
                  {"air_temperature_c", "20"},
                  {"air_pressure_pa", "100000"}};
  int line = 8;
  for (double x : pwms) {
    log.column(pe::BenchColumn::kPwm).push_back(x);
    log.column(pe::BenchColumn::kVoltage).push_back(voltage);
    log.column(pe::BenchColumn::kThrust).push_back(thrust_g(x, voltage) * pe::kNewtonPerGramForce);
    log.line_numbers.push_back(line++);
  }
  return log;
}

std::vector<double> pwmSteps(double from, double to, double step) {
  std::vector<double> values;
  for (double x = from; x <= to + 1e-9; x += step) values.push_back(x);
  return values;
}

double smoothThrust(double x, double v) { return SmoothChain::thrustGrams(x, v); }

}  // namespace

// --- the simulator's sweeps: the held-out voltage level within the noise -------------------------

TEST(BenchFit, RecoversEachHeldOutVoltageLevelOfTheSimulatedSweepWithinItsNoise) {
  const SweepSet set = simulatedSweeps();
  ASSERT_EQ(set.logs.size(), 8u);
  EXPECT_GT(set.thrust_sigma_g, 0.5);  // the sensors did add noise
  // Every interior level in turn (the two end levels would test extrapolation, not the model).
  for (std::size_t held_out = 1; held_out + 1 < set.logs.size(); ++held_out) {
    std::vector<pe::BenchLog> training;
    for (std::size_t k = 0; k < set.logs.size(); ++k) {
      if (k != held_out) training.push_back(set.logs[k]);
    }
    const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(training, {});
    ASSERT_TRUE(fit.validation_error.empty()) << fit.validation_error;
    EXPECT_EQ(fit.grouping, pe::fitting::FitGrouping::kVoltageLevel);
    const pe::BenchLog& test = set.logs[held_out];
    EXPECT_LT(rmseOn(fit.model, pe::Output::kThrust, test), 1.5 * set.thrust_sigma_g) << held_out;
    EXPECT_LT(rmseOn(fit.model, pe::Output::kCurrent, test), 1.5 * set.current_sigma_a) << held_out;
    EXPECT_LT(rmseOn(fit.model, pe::Output::kPower, test), 1.5 * set.power_sigma_w) << held_out;
    EXPECT_LT(rmseOn(fit.model, pe::Output::kRpm, test), 1.5 * set.rpm_sigma) << held_out;
  }
}

TEST(BenchFit, SurfaceFollowsTheNoiseFreeChainAndReportsHonestErrors) {
  const SweepSet set = syntheticSweeps(7);
  const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(set.logs, {});
  ASSERT_TRUE(fit.validation_error.empty()) << fit.validation_error;
  EXPECT_EQ(fit.grouping_description, "leave one voltage level out (8 levels, 10.50 to 12.60 V)");
  // Against the truth on a grid, the surface is much closer than one noise sigma (1128 samples).
  double sse = 0.0;
  int n = 0;
  for (double x = 1200.0; x <= 1900.0; x += 20.0) {
    for (double v = 10.5; v <= 12.6001; v += 0.15) {
      const double error = fit.model.evaluateRaw(pe::Output::kThrust, x, v) - SmoothChain::thrustGrams(x, v);
      sse += error * error;
      ++n;
    }
  }
  EXPECT_LT(std::sqrt(sse / n), 0.5 * set.thrust_sigma_g);
  const pe::fitting::OutputFitReport& thrust = fit.outputs[static_cast<int>(pe::Output::kThrust)];
  EXPECT_EQ(thrust.points, 8 * 141);
  // In-sample and held-out errors both estimate the noise.
  EXPECT_NEAR(thrust.rmse, set.thrust_sigma_g, 0.15 * set.thrust_sigma_g);
  const pe::FitQuality& quality = *fit.model.output(pe::Output::kThrust).fit;
  EXPECT_NEAR(quality.held_out_rmse, set.thrust_sigma_g, 0.2 * set.thrust_sigma_g);
  EXPECT_GE(quality.held_out_rmse, thrust.rmse);
  EXPECT_GT(thrust.r2, 0.999);
  EXPECT_GT(thrust.max_error, 2.5 * set.thrust_sigma_g);  // the largest of 1128 normal residuals
  EXPECT_LT(thrust.max_error, 5.0 * set.thrust_sigma_g);
  // Degrees: 20 candidates scored; thrust ~ rpm^2 is (4, 2) in the chain, power needs more PWM terms.
  EXPECT_EQ(thrust.candidates.size(), 23u);  // 20 polyXY degree pairs and drive curves of degree 1 to 3
  EXPECT_GE(quality.pwm_degree, 3);
  EXPECT_GE(quality.voltage_degree, 1);
  EXPECT_EQ(fit.model.output(pe::Output::kEfficiency).source, pe::OutputSource::kDerived);
  // The domain and scaling come from the data.
  EXPECT_DOUBLE_EQ(fit.model.domain().pwm_min_us, 1200.0);
  EXPECT_DOUBLE_EQ(fit.model.domain().pwm_max_us, 1900.0);
  EXPECT_NEAR(fit.model.domain().voltage_min_v, 10.5, 0.05);
  EXPECT_NEAR(fit.model.domain().voltage_max_v, 12.6, 0.05);
  const pe::InputScaling& s = fit.model.output(pe::Output::kThrust).surface->scaling();
  EXPECT_DOUBLE_EQ(s.pwm_center_us, 1550.0);
  EXPECT_DOUBLE_EQ(s.pwm_scale_us, 350.0);
  EXPECT_EQ(fit.model.metadata().motor, "synthetic 920KV");
  EXPECT_EQ(fit.model.metadata().source,
            "fit_surfaces from sweep_0.csv, sweep_1.csv, sweep_2.csv, sweep_3.csv, ... (8 logs)");
}

TEST(BenchFit, FittedModelFileLoadsUnchanged) {
  const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(syntheticSweeps().logs, {});
  const std::string path = (std::filesystem::temp_directory_path() / "pe_fitted_model.yaml").string();
  pe::saveModelFile(fit.model, path);
  const pe::PropulsionModel loaded = pe::loadModelFile(path);
  for (double x : {1200.0, 1433.0, 1900.0}) {
    for (double v : {10.5, 11.7, 12.6}) {
      for (pe::Output output : pe::kAllOutputs) {
        EXPECT_DOUBLE_EQ(loaded.evaluateRaw(output, x, v), fit.model.evaluateRaw(output, x, v));
      }
    }
  }
  const pe::FitQuality& q = *loaded.output(pe::Output::kRpm).fit;
  const pe::FitQuality& original = *fit.model.output(pe::Output::kRpm).fit;
  EXPECT_EQ(q.pwm_degree, original.pwm_degree);
  EXPECT_EQ(q.points, original.points);
  EXPECT_DOUBLE_EQ(q.held_out_rmse, original.held_out_rmse);
  EXPECT_EQ(q.grouping, original.grouping);
  std::filesystem::remove(path);
}

// --- battery discharges: no discrete levels, rows binned by voltage ------------------------------

TEST(BenchFit, BinsContinuousBatteryDischargesIntoVoltageLevels) {
  // Thesis 4.2: constant PWM 1600..1900 us while a 3S battery runs down from 12.6 to 10.5 V.
  std::vector<pe::BenchLog> logs;
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 2.0);
  for (double pwm : {1600.0, 1700.0, 1800.0, 1900.0}) {
    pe::BenchLog log;
    log.source = "discharge_" + std::to_string(static_cast<int>(pwm)) + ".csv";
    log.metadata = {{"esc", "E"},
                    {"motor", "M"},
                    {"propeller", "P"},
                    {"supply", "battery"},
                    {"air_temperature_c", "20"},
                    {"air_pressure_pa", "100000"}};
    for (int k = 0; k <= 400; ++k) {
      const double v = 12.6 - 2.1 * k / 400.0;
      log.column(pe::BenchColumn::kPwm).push_back(pwm);
      log.column(pe::BenchColumn::kVoltage).push_back(v);
      log.column(pe::BenchColumn::kThrust).push_back((smoothThrust(pwm, v) + noise(random)) * pe::kNewtonPerGramForce);
      log.line_numbers.push_back(k + 2);
    }
    logs.push_back(std::move(log));
  }
  const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(logs, {});
  // 10.5..12.6 V in 0.3 V bins anchored at 0 V: [10.5, 10.8), ..., [12.3, 12.6), [12.6, 12.9).
  ASSERT_EQ(fit.data.voltage_levels.size(), 8u);
  EXPECT_NEAR(fit.data.voltage_levels.front().centre, 10.65, 1e-9);
  EXPECT_EQ(fit.grouping, pe::fitting::FitGrouping::kVoltageLevel);
  EXPECT_EQ(fit.notes[0],
            "discharge_1600.csv: voltage varies (10.50 to 12.60 V): its rows are binned by voltage in 0.3 V bins");
  // Four PWM levels: a held-out voltage bin still sees all four, so PWM degree <= 3.
  EXPECT_LE(fit.model.output(pe::Output::kThrust).fit->pwm_degree, 3);
  for (double pwm : {1600.0, 1750.0, 1900.0}) {
    for (double v : {10.6, 11.5, 12.5}) {
      EXPECT_NEAR(fit.model.evaluateRaw(pe::Output::kThrust, pwm, v), smoothThrust(pwm, v), 3.0) << pwm << " " << v;
    }
  }
}

// --- the thesis: surfaces sampled on its grid are fitted back to its chapter 7 maxima ------------

TEST(BenchFit, ThesisSurfacesSampledOnItsGridReproduceChapter7Maxima) {
  const pe::PropulsionModel thesis = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  std::mt19937 random(11);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<pe::BenchLog> logs;
  for (int level = 0; level < 8; ++level) {
    const double v = 10.5 + 0.3 * level;
    pe::BenchLog log;
    log.source = "thesis_" + std::to_string(level) + ".csv";
    log.metadata = {{"esc", "DJI E300"},     {"motor", "DJI 2212 920KV"}, {"propeller", "DJI 9443"},
                    {"supply", "regulated"}, {"air_temperature_c", "22"}, {"air_pressure_pa", "101325"}};
    for (double x = 1200.0; x <= 1900.0; x += 5.0) {
      log.column(pe::BenchColumn::kPwm).push_back(x);
      log.column(pe::BenchColumn::kVoltage).push_back(v);
      log.column(pe::BenchColumn::kThrust)
          .push_back((thesis.evaluateRaw(pe::Output::kThrust, x, v) + 1.0 * unit(random)) * pe::kNewtonPerGramForce);
      log.column(pe::BenchColumn::kCurrent)
          .push_back(thesis.evaluateRaw(pe::Output::kCurrent, x, v) + 0.02 * unit(random));
      log.column(pe::BenchColumn::kPower).push_back(thesis.evaluateRaw(pe::Output::kPower, x, v) + 0.2 * unit(random));
      log.column(pe::BenchColumn::kRpm).push_back(thesis.evaluateRaw(pe::Output::kRpm, x, v) + 10.0 * unit(random));
      log.line_numbers.push_back(static_cast<int>(log.rows()) + 2);
    }
    logs.push_back(std::move(log));
  }
  const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(logs, {});
  ASSERT_TRUE(fit.validation_error.empty()) << fit.validation_error;
  // Chapter 7, table 7.1-7.6, E300-2212 with the 9443 propeller at 12.6 V.
  double thrust = 0, current = 0, power = 0, efficiency_at_max_power = 0, rpm = 0;
  for (double x = 1200.0; x <= 1900.0; x += 5.0) {
    pe::OperatingPoint e;
    ASSERT_TRUE(fit.model.evaluate(x, 12.6, &e));
    thrust = std::max(thrust, e.thrust_n / pe::kNewtonPerGramForce);
    current = std::max(current, e.current_a);
    rpm = std::max(rpm, e.rpm);
    if (e.power_w > power) {
      power = e.power_w;
      efficiency_at_max_power = e.efficiency_n_per_w / pe::kNewtonPerGramForce;
    }
  }
  EXPECT_NEAR(thrust, 681.85, 0.03 * 681.85);
  EXPECT_NEAR(current, 8.89, 0.03 * 8.89);
  EXPECT_NEAR(power, 112.12, 0.03 * 112.12);
  EXPECT_NEAR(efficiency_at_max_power, 6.28, 0.03 * 6.28);
  EXPECT_NEAR(rpm, 8682.0, 0.03 * 8682.0);
  // The thesis' thrust is poly21: a (2, 1) surface or one containing it.
  const pe::FitQuality& q = *fit.model.output(pe::Output::kThrust).fit;
  EXPECT_GE(q.pwm_degree, 2);
  EXPECT_GE(q.voltage_degree, 1);
  EXPECT_LT(q.held_out_rmse, 1.3);
}

// --- real data: Strawson's RCbenchmark exports, two supply levels per combination ---------------

TEST(BenchFitStrawson, FitsAMotorPropellerPairFromItsTwoSupplyLevels) {
  // Lumenier RX2206-13 2000kv with the Cyclone T5040C: no current limit was hit.
  const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(
      strawsonPair("g1"), strawsonOptions("Lumenier RX2206-13 2000kv", "Cyclone T5040C 3-blade"));
  ASSERT_TRUE(fit.validation_error.empty()) << fit.validation_error;
  EXPECT_EQ(fit.grouping, pe::fitting::FitGrouping::kPwmLevel);
  EXPECT_EQ(fit.grouping_description,
            "leave one PWM level out (11 levels, 1050 to 2000 us); 2 voltage levels only, so the voltage degree is at "
            "most 1");
  ASSERT_EQ(fit.data.voltage_levels.size(), 2u);
  EXPECT_NEAR(fit.data.voltage_levels[0].centre, 7.39, 0.05);
  EXPECT_NEAR(fit.data.voltage_levels[1].centre, 11.06, 0.05);
  // Thrust 2..340 gf, current to 6.9 A, power to 75 W, electrical rpm to 16k.
  struct Bound {
    pe::Output output;
    double min_r2, max_rmse, max_held_out;
  };
  for (const Bound& b : {Bound{pe::Output::kThrust, 0.999, 3.0, 8.0}, Bound{pe::Output::kCurrent, 0.998, 0.1, 0.25},
                         Bound{pe::Output::kPower, 0.998, 1.0, 2.5}, Bound{pe::Output::kRpm, 0.995, 250.0, 700.0}}) {
    const pe::fitting::OutputFitReport& report = fit.outputs[static_cast<int>(b.output)];
    const pe::FitQuality& q = *fit.model.output(b.output).fit;
    EXPECT_EQ(report.points, 22) << pe::outputName(b.output);
    EXPECT_GT(report.r2, b.min_r2) << pe::outputName(b.output);
    EXPECT_LT(report.rmse, b.max_rmse) << pe::outputName(b.output);
    EXPECT_LT(q.held_out_rmse, b.max_held_out) << pe::outputName(b.output);
    EXPECT_GE(q.held_out_rmse, report.rmse) << pe::outputName(b.output);
    EXPECT_LE(q.voltage_degree, 1) << pe::outputName(b.output);
    EXPECT_LE(report.max_error, 4.0 * report.rmse) << pe::outputName(b.output);
  }
  // Physically: more thrust at 3S than at 2S at the same command, both near the logged values.
  EXPECT_NEAR(fit.model.evaluateRaw(pe::Output::kThrust, 2000.0, 10.9), 340.0, 8.0);
  EXPECT_NEAR(fit.model.evaluateRaw(pe::Output::kThrust, 2000.0, 7.3), 162.0, 8.0);

  const std::string path = (std::filesystem::temp_directory_path() / "pe_g1.yaml").string();
  pe::saveModelFile(fit.model, path);
  const pe::PropulsionModel loaded = pe::loadModelFile(path);
  EXPECT_DOUBLE_EQ(loaded.evaluateRaw(pe::Output::kThrust, 1500.0, 9.0),
                   fit.model.evaluateRaw(pe::Output::kThrust, 1500.0, 9.0));
  EXPECT_EQ(loaded.metadata().propeller, "Cyclone T5040C 3-blade");
  std::filesystem::remove(path);
}

TEST(BenchFitStrawson, KeepsAndReportsRowsWhereTheSupplyCurrentLimitCollapsedTheVoltage) {
  // a1_11: at 1905 and 2000 us the supply's ~11 A limit pulled 11 V down to 9.35 and 8.30 V.
  const pe::fitting::BenchFit fit =
      pe::fitting::fitBenchModel(strawsonPair("a1"), strawsonOptions("EMAX RS2205S 2600kv", "T5040C"));
  ASSERT_TRUE(fit.validation_error.empty()) << fit.validation_error;
  const std::string expected = repoPath(kStrawson + "a1_11.csv") +
                               ": 2 rows more than 0.5 V off the sweep's 10.99 V (down to 8.30 V at 2000 us, 10.96 A): "
                               "the supply sagged; these rows are fitted at their measured voltage";
  EXPECT_NE(std::find(fit.notes.begin(), fit.notes.end(), expected), fit.notes.end());
  // The sagged rows are still two levels' worth of data, not four.
  EXPECT_EQ(fit.data.voltage_levels.size(), 2u);
  // The domain is what the model was measured on: every row at its voltage. Its 7.14 V bound is
  // a1_7's own top-of-sweep droop (0.18 V under its median), and the report says where it lies.
  EXPECT_NEAR(fit.model.domain().voltage_min_v, 7.14, 0.01);
  const std::string report = pe::fitting::fitReportMarkdown(fit, "a1.yaml");
  EXPECT_NE(report.find("- Domain: PWM 1050 to 2000 us, voltage 7.14 to 11.09 V at the rows' measured voltage (7.14 V "
                        "was logged at 2000 us, 11.09 V at 1050 us). Within that box the model's domain is only what "
                        "the bench covered, the voltage range logged at each PWM level (interpolated between levels); "
                        "outside it the model will clamp, and the estimator flags the sample.\n"),
            std::string::npos)
      << report;
  // At 2000 us the bench went from a1_7's droop to a1_11's collapse, nowhere else.
  EXPECT_NE(report.find("| 2000 | 7.14 to 8.30 |\n"), std::string::npos) << report;
  // At the collapsed point the surface matches the measured 377 gf at 8.30 V.
  EXPECT_NEAR(fit.model.evaluateRaw(pe::Output::kThrust, 2000.0, 8.304389367087847), 376.9, 6.0);
}

TEST(BenchFitStrawson, RefusesAPairWhoseTwoFilesAreAtTheSameVoltage) {
  // l3_11.csv is named 3S but was logged at 2S: its voltage is 7.15..7.43 V like l3_7.csv.
  EXPECT_EQ(refusal(strawsonPair("l3"), strawsonOptions("T-Motor F30", "Gemfan 5x4.5")),
            "cannot fit a surface: one voltage level only (all 22 rows of " + repoPath(kStrawson + "l3_7.csv") +
                " and " + repoPath(kStrawson + "l3_11.csv") +
                " have voltage_v near 7.36 V, 7.13 to 7.44 V); log sweeps at two or more supply voltages, or a "
                "battery discharge");
}

TEST(BenchFitStrawson, RefusesAGroupingThatLeavesOneVoltageLevelPerFold) {
  // Two supply levels: holding out a level, or one of the two logs, leaves nothing to fit voltage
  // on, and every candidate would have voltage degree 0: a model that ignores voltage.
  pe::fitting::FitOptions options = strawsonOptions("Lumenier RX2206-13 2000kv", "Cyclone T5040C 3-blade");
  options.grouping = pe::fitting::FitGrouping::kVoltageLevel;
  EXPECT_EQ(refusal(strawsonPair("g1"), options),
            "cannot fit thrust: --group-by voltage leaves one voltage level in a training fold (without the 7.40 V "
            "level only 11.07 V remains), so cross-validation cannot score a voltage term: use --group-by pwm or "
            "auto");
  options.grouping = pe::fitting::FitGrouping::kLog;
  EXPECT_EQ(refusal(strawsonPair("g1"), options),
            "cannot fit thrust: --group-by log leaves one voltage level in a training fold (without " +
                repoPath(kStrawson + "g1_7.csv") +
                " only 11.07 V remains), so cross-validation cannot score a voltage term: use --group-by pwm or auto");
}

// --- refusals --------------------------------------------------------------------------------------

TEST(BenchFitRefusals, OneVoltageLevel) {
  EXPECT_EQ(
      refusal({gridLog("a.csv", pwmSteps(1100, 1900, 100), 11.1, smoothThrust),
               gridLog("b.csv", pwmSteps(1150, 1850, 100), 11.12, smoothThrust)}),
      "cannot fit a surface: one voltage level only (all 17 rows of a.csv and b.csv have voltage_v near 11.11 V, "
      "11.10 to 11.12 V); log sweeps at two or more supply voltages, or a battery discharge");
}

TEST(BenchFitRefusals, TooFewPwmLevels) {
  EXPECT_EQ(
      refusal({gridLog("a.csv", {1500, 1600}, 11.1, smoothThrust), gridLog("b.csv", {1500, 1600}, 12.0, smoothThrust)}),
      "cannot fit a surface: 2 PWM levels only (pwm_us of a.csv and b.csv: 1500 us, 1600 us); log sweeps over at "
      "least 3 PWM values");
}

TEST(BenchFitRefusals, TooFewPoints) {
  EXPECT_EQ(refusal({gridLog("a.csv", {1200, 1500, 1800}, 11.1, smoothThrust),
                     gridLog("b.csv", {1200, 1500, 1800}, 12.0, smoothThrust)}),
            "cannot fit thrust: 6 rows of a.csv and b.csv have thrust_n, at least 10 are needed");
}

TEST(BenchFitRefusals, ConstantColumn) {
  std::vector<pe::BenchLog> logs = {gridLog("a.csv", pwmSteps(1100, 1900, 100), 11.1, smoothThrust),
                                    gridLog("b.csv", pwmSteps(1100, 1900, 100), 12.0, smoothThrust)};
  for (pe::BenchLog& log : logs) log.column(pe::BenchColumn::kRpm).assign(log.rows(), 0.0);
  EXPECT_EQ(
      refusal(logs),
      "cannot fit rpm: column rpm is 0 rpm in all 18 rows of a.csv and b.csv (a sensor that was not connected?); "
      "leave it out with --without rpm");
  pe::fitting::FitOptions without_rpm;
  without_rpm.without = {pe::Output::kRpm};
  const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(logs, without_rpm);
  EXPECT_EQ(fit.model.output(pe::Output::kRpm).source, pe::OutputSource::kNone);
  EXPECT_EQ(fit.model.output(pe::Output::kRpm).note, "left out on request (--without rpm)");
  for (pe::BenchLog& log : logs) log.column(pe::BenchColumn::kThrust).assign(log.rows(), 0.0);
  EXPECT_EQ(refusal(logs, without_rpm),
            "cannot fit thrust: column thrust_n is 0 g in all 18 rows of a.csv and b.csv (a sensor that was not "
            "connected?)");
}

// A current column that is noise (a misread sensor) is left out, and the advice names a --map the
// reader takes: the bench quantity current_a, not the output's name.
TEST(BenchFit, LeavesOutACurrentThatIsNoiseNamingTheMapToTry) {
  std::vector<pe::BenchLog> logs = {gridLog("a.csv", pwmSteps(1100, 1900, 50), 11.1, smoothThrust),
                                    gridLog("b.csv", pwmSteps(1100, 1900, 50), 12.0, smoothThrust),
                                    gridLog("c.csv", pwmSteps(1100, 1900, 50), 12.6, smoothThrust)};
  std::mt19937 draw(3);
  std::uniform_real_distribution<double> noise(1.0, 20.0);
  for (pe::BenchLog& log : logs) {
    for (std::size_t row = 0; row < log.rows(); ++row) log.column(pe::BenchColumn::kCurrent).push_back(noise(draw));
  }
  const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(logs, {});
  ASSERT_EQ(fit.model.output(pe::Output::kCurrent).source, pe::OutputSource::kNone);
  const std::string& note = fit.model.output(pe::Output::kCurrent).note;
  EXPECT_NE(note.find("of column current_a (a noisy or misread sensor?): map another column with --map "
                      "current_a=<column>"),
            std::string::npos)
      << note;
}

// Grams logged under thrust_n (a hundred times the thrust) or newtons under thrust_g: thrust over
// power is then far from any propeller's, and the log is refused, not fitted.
TEST(BenchFitRefusals, ThrustOrPowerInOtherUnits) {
  const auto logsWithThrustTimes = [](double scale) {
    std::vector<pe::BenchLog> logs = {gridLog("a.csv", pwmSteps(1100, 1900, 100), 11.1, smoothThrust),
                                      gridLog("b.csv", pwmSteps(1100, 1900, 100), 12.0, smoothThrust)};
    for (pe::BenchLog& log : logs) {
      for (std::size_t row = 0; row < log.rows(); ++row) {
        const double x = log.column(pe::BenchColumn::kPwm)[row], v = log.column(pe::BenchColumn::kVoltage)[row];
        log.column(pe::BenchColumn::kPower).push_back(SmoothChain::powerWatts(x, v));
        log.column(pe::BenchColumn::kThrust)[row] *= scale;
      }
    }
    return logs;
  };
  for (double scale : {1.0 / pe::kNewtonPerGramForce, pe::kNewtonPerGramForce}) {
    const std::string line = refusal(logsWithThrustTimes(scale));
    EXPECT_EQ(line.rfind("a.csv: thrust over power is ", 0), 0u) << line;
    EXPECT_NE(line.find(" g/W (the median), where propellers give 0.5-40 g/W: thrust or power logged in other units "
                        "(grams under thrust_n, newtons under thrust_g, mW or kW)?"),
              std::string::npos)
        << line;
  }
  EXPECT_EQ(refusal(logsWithThrustTimes(1.0)), "accepted");
}

TEST(BenchFitRefusals, AnOutputLoggedAtOneVoltageLevelOnly) {
  // rpm in the 11.1 V sweep only: its surface could not depend on voltage.
  std::vector<pe::BenchLog> logs = {gridLog("a.csv", pwmSteps(1100, 1900, 50), 11.1, smoothThrust),
                                    gridLog("b.csv", pwmSteps(1100, 1900, 50), 12.0, smoothThrust)};
  for (double x : logs[0].column(pe::BenchColumn::kPwm)) {
    logs[0].column(pe::BenchColumn::kRpm).push_back(SmoothChain::rpm(x, 11.1));
  }
  EXPECT_EQ(refusal(logs), "cannot fit rpm: all 17 rows of a.csv with rpm are at one voltage level (11.10 V); log it at "
                           "two or more voltages or leave it out with --without rpm");
}

TEST(BenchFitRefusals, NaNInALog) {
  std::vector<pe::BenchLog> logs = {gridLog("a.csv", pwmSteps(1100, 1900, 100), 11.1, smoothThrust),
                                    gridLog("b.csv", pwmSteps(1100, 1900, 100), 12.0, smoothThrust)};
  logs[1].column(pe::BenchColumn::kThrust)[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(refusal(logs), "b.csv:11: thrust_n: nan is not a finite number");
}

TEST(BenchFitRefusals, MissingOrContradictoryMetadata) {
  std::vector<pe::BenchLog> logs = {gridLog("a.csv", pwmSteps(1100, 1900, 100), 11.1, smoothThrust),
                                    gridLog("b.csv", pwmSteps(1100, 1900, 100), 12.0, smoothThrust)};
  logs[1].metadata["motor"] = "other";
  EXPECT_EQ(refusal(logs),
            "logs disagree on motor: 'M' (a.csv) and 'other' (b.csv); pass --motor to say which the model records");
  for (pe::BenchLog& log : logs) log.metadata.erase("air_temperature_c");
  pe::fitting::FitOptions motor;
  motor.motor = "M";
  EXPECT_EQ(refusal(logs, motor),
            "no log gives the bench's air_temperature_c (a '# air_temperature_c:' line or an ambient_temp_c column): "
            "pass --air-temperature-c");
  logs[0].column(pe::BenchColumn::kAmbientTemp).assign(logs[0].rows(), 24.0);
  const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(logs, motor);
  EXPECT_DOUBLE_EQ(fit.model.metadata().bench_air_temperature_c.value(), 24.0);
  EXPECT_EQ(fit.model.metadata().supply, pe::SupplyKind::kBattery);
}

TEST(BenchFitRefusals, EveryMissingBenchConditionInOneMessageAndUnknownNames) {
  std::vector<pe::BenchLog> logs = {gridLog("a.csv", pwmSteps(1100, 1900, 100), 11.1, smoothThrust),
                                    gridLog("b.csv", pwmSteps(1100, 1900, 100), 12.0, smoothThrust)};
  for (pe::BenchLog& log : logs) log.metadata.clear();
  EXPECT_EQ(refusal(logs),
            "no log gives the bench's air_temperature_c (a '# air_temperature_c:' line or an ambient_temp_c column), "
            "air_pressure_pa (a '# air_pressure_pa:' line or a pressure_pa column) and supply (a '# supply:' line): "
            "pass --air-temperature-c, --air-pressure-pa and --supply");
  pe::fitting::FitOptions physics;
  physics.supply = pe::SupplyKind::kRegulated;
  physics.air_pressure_pa = 101325.0;
  EXPECT_EQ(refusal(logs, physics),
            "no log gives the bench's air_temperature_c (a '# air_temperature_c:' line or an ambient_temp_c column): "
            "pass --air-temperature-c");
  // The names only describe the combination: without them the model says "unknown", and the notes why.
  physics.air_temperature_c = 20.0;
  physics.propeller = "DJI 9443";
  const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(logs, physics);
  EXPECT_EQ(fit.model.metadata().esc, "unknown");
  EXPECT_EQ(fit.model.metadata().motor, "unknown");
  EXPECT_EQ(fit.model.metadata().propeller, "DJI 9443");
  for (const char* key : {"esc", "motor"}) {
    const std::string note = std::string(key) + ": no log has a '# " + key + ":' line; the model records 'unknown' " +
                             "(pass --" + key + " to name it)";
    EXPECT_NE(std::find(fit.notes.begin(), fit.notes.end(), note), fit.notes.end()) << note;
    EXPECT_NE(pe::fitting::fitReportMarkdown(fit, "m.yaml").find("- " + note + "\n"), std::string::npos) << note;
  }
}

TEST(BenchFitRefusals, RefusesAThrustThatFallsAsPwmRises) {
  // A stand wired so that thrust reads negative, passed on without a sign correction: no surface
  // that rises with PWM fits it, and the fit says so instead of writing one that falls.
  auto negative = [](double x, double v) { return -0.1 * (x - 1100.0) + 0.0 * v; };
  EXPECT_EQ(
      refusal({gridLog("a.csv", pwmSteps(1100, 1900, 50), 11.1, negative),
               gridLog("b.csv", pwmSteps(1100, 1900, 50), 12.0, negative)}),
      "cannot fit thrust: no candidate surface rises with PWM and voltage over the bench's domain (does column "
      "thrust_n fall as PWM rises? a sensor read with the wrong sign)");
}

TEST(BenchFitRefusals, BadOptions) {
  const std::vector<pe::BenchLog> logs = syntheticSweeps().logs;
  pe::fitting::FitOptions options;
  options.max_pwm_degree = 6;
  EXPECT_EQ(refusal(logs, options), "max PWM degree 6 is outside 1..5");
  options = {};
  options.without = {pe::Output::kThrust};
  EXPECT_EQ(refusal(logs, options), "thrust cannot be left out: it is what the estimator is for");
  options = {};
  options.levels.steady_voltage_mad_v = 0.0;
  EXPECT_EQ(refusal(logs, options), "--steady-voltage-mad: 0 V is not positive");
  options = {};
  options.levels.voltage_bin_v = -0.3;
  EXPECT_EQ(refusal(logs, options), "--voltage-bin: -0.3 V is not positive");
}

TEST(BenchFitRefusals, BenchAirTheModelLoaderWouldRefuse) {
  std::vector<pe::BenchLog> logs = {gridLog("a.csv", pwmSteps(1100, 1900, 100), 11.1, smoothThrust),
                                    gridLog("b.csv", pwmSteps(1100, 1900, 100), 12.0, smoothThrust)};
  pe::fitting::FitOptions kelvin;
  kelvin.air_temperature_c = 293.15;
  EXPECT_EQ(refusal(logs, kelvin),
            "metadata.bench_air_temperature_c: 293.15 is not an air temperature in deg C (given as "
            "--air-temperature-c)");
  // A pressure column logged in hPa.
  for (pe::BenchLog& log : logs) {
    log.metadata.erase("air_pressure_pa");
    log.column(pe::BenchColumn::kPressure).assign(log.rows(), 1013.25);
  }
  EXPECT_EQ(refusal(logs),
            "metadata.bench_air_pressure_pa: 1013.25 is not an air pressure in Pa (from a.csv column pressure_pa and "
            "b.csv column pressure_pa; pass --air-pressure-pa)");
  pe::fitting::FitOptions pascal;
  pascal.air_pressure_pa = 101325.0;
  EXPECT_DOUBLE_EQ(pe::fitting::fitBenchModel(logs, pascal).model.metadata().bench_air_pressure_pa.value(), 101325.0);
}

TEST(BenchFitRefusals, LogsBuiltInCodeThatBreakTheReadersGuarantees) {
  const pe::BenchLog good = gridLog("a.csv", pwmSteps(1100, 1900, 100), 11.1, smoothThrust);
  auto dataset = [&](const pe::BenchLog& log) {
    try {
      pe::fitting::buildBenchDataset({good, log}, {});
    } catch (const pe::DataError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(dataset(gridLog("e.csv", {}, 12.0, smoothThrust)), "e.csv: the log has no rows");
  pe::BenchLog short_column = gridLog("s.csv", pwmSteps(1100, 1900, 100), 12.0, smoothThrust);
  short_column.column(pe::BenchColumn::kCurrent).assign(8, 1.0);
  EXPECT_EQ(dataset(short_column), "s.csv: column current_a has 8 values for 9 rows");
  pe::BenchLog long_column = gridLog("l.csv", pwmSteps(1100, 1900, 100), 12.0, smoothThrust);
  long_column.column(pe::BenchColumn::kPwm).push_back(2000.0);
  EXPECT_EQ(dataset(long_column), "l.csv: column pwm_us has 10 values for 9 rows");
  pe::BenchLog no_voltage = gridLog("v.csv", pwmSteps(1100, 1900, 100), 12.0, smoothThrust);
  no_voltage.column(pe::BenchColumn::kVoltage).clear();
  EXPECT_EQ(dataset(no_voltage), "v.csv: column voltage_v is missing (required: pwm_us, voltage_v, thrust_n)");
  EXPECT_EQ(dataset(gridLog("b.csv", pwmSteps(1100, 1900, 100), 12.0, smoothThrust)), "accepted");
}

TEST(BenchFit, EfficiencyAsItsOwnSurfaceOnRequest) {
  pe::fitting::FitOptions options;
  options.efficiency_surface = true;
  const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(syntheticSweeps().logs, options);
  ASSERT_EQ(fit.model.output(pe::Output::kEfficiency).source, pe::OutputSource::kSurface);
  // Thrust / power of the chain at 1700 us, 11.7 V.
  const double truth = SmoothChain::thrustGrams(1700, 11.7) / SmoothChain::powerWatts(1700, 11.7);
  EXPECT_NEAR(fit.model.evaluateRaw(pe::Output::kEfficiency, 1700, 11.7), truth, 0.05 * truth);
}

TEST(BenchFit, GroupingByLogOnRequest) {
  pe::fitting::FitOptions options;
  options.grouping = pe::fitting::FitGrouping::kLog;
  const pe::fitting::BenchFit fit = pe::fitting::fitBenchModel(syntheticSweeps().logs, options);
  EXPECT_EQ(fit.grouping_description, "leave one log out (8 logs)");
  EXPECT_EQ(fit.model.output(pe::Output::kThrust).fit->grouping, "leave one log out (8 logs)");
  // Two logs per voltage level: every fold keeps both levels, and voltage is fitted.
  const pe::fitting::BenchFit repeated =
      pe::fitting::fitBenchModel({gridLog("a.csv", pwmSteps(1100, 1900, 100), 11.1, smoothThrust),
                                  gridLog("b.csv", pwmSteps(1150, 1850, 100), 11.1, smoothThrust),
                                  gridLog("c.csv", pwmSteps(1100, 1900, 100), 12.3, smoothThrust),
                                  gridLog("d.csv", pwmSteps(1150, 1850, 100), 12.3, smoothThrust)},
                                 options);
  EXPECT_EQ(repeated.data.voltage_levels.size(), 2u);
  EXPECT_EQ(repeated.model.output(pe::Output::kThrust).fit->voltage_degree, 1);
}
