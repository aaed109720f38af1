#include "fit_surfaces_command.h"

#include <algorithm>
#include <cmath>
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "bench_log_options.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/fitting/rpm_thrust_fit.h"
#include "propulsion_estimator/fitting/surface_fit.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/fitting/fit_report.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/common/yaml_map.h"
#include "report_plotter.h"
#include "tool_command.h"

namespace propulsion_estimator {
namespace {

struct Arguments {
  std::vector<std::string> logs;
  std::string out;
  std::string report;
  std::string group_by = "auto";
  std::string efficiency = "derived";
  std::vector<std::string> without;
  std::string outside = "clamp";
  std::optional<std::string> supply;
  ReportPlotter plotter;
};

void printSummary(const fitting::BenchFit& fit) {
  std::printf("%-10s %-8s %-10s %6s %9s %10s %10s %10s\n", "output", "model", "degrees", "points", "R^2", "RMSE",
              "max error", "held-out");
  for (Output output : kAllOutputs) {
    const OutputDefinition& def = fit.model.output(output);
    const fitting::OutputFitReport& report = fit.outputs[static_cast<int>(output)];
    if (def.source == OutputSource::kNone) {
      std::printf("%-10s none: %s\n", outputName(output), def.note.c_str());
      continue;
    }
    std::string degrees;
    if (def.fit && def.fit->basis == "drive_curve") {
      degrees = "drive " + std::to_string(def.fit->pwm_degree) +
                (std::isfinite(def.surface->driveCurve()->pwmFullUs()) ? "+ft" : "");
    } else if (def.fit) {
      degrees = "(" + std::to_string(def.fit->pwm_degree) + "," + std::to_string(def.fit->voltage_degree) + ")";
    }
    std::printf("%-10s %-8s %-10s %6d %9.5f %10.4g %10.4g", outputName(output),
                def.source == OutputSource::kSurface ? "surface" : "derived", degrees.c_str(), report.points, report.r2,
                report.rmse, report.max_error);
    if (def.fit) std::printf(" %10.4g", def.fit->held_out_rmse);
    std::printf("  %s\n", def.unit.c_str());
  }
}

int fit(const Arguments& args, fitting::FitOptions options, const BenchReadOptions& read_options) {
  static const std::map<std::string, fitting::FitGrouping> kGroupings = {
      {"auto", fitting::FitGrouping::kAuto},
      {"voltage", fitting::FitGrouping::kVoltageLevel},
      {"pwm", fitting::FitGrouping::kPwmLevel},
      {"log", fitting::FitGrouping::kLog}};
  static const std::map<std::string, OutsideDomain> kOutside = {{"clamp", OutsideDomain::kClamp},
                                                                {"extrapolate", OutsideDomain::kExtrapolate},
                                                                {"reject", OutsideDomain::kReject}};
  static const std::map<std::string, Output> kOptional = {
      {"current", Output::kCurrent}, {"power", Output::kPower}, {"rpm", Output::kRpm}};
  options.grouping = kGroupings.at(args.group_by);
  options.outside = kOutside.at(args.outside);
  options.efficiency_surface = args.efficiency == "surface";
  for (const std::string& name : args.without) options.without.insert(kOptional.at(name));
  if (args.supply) options.supply = *args.supply == "battery" ? SupplyKind::kBattery : SupplyKind::kRegulated;

  if (!args.report.empty()) args.plotter.check();  // before the fit, which may take a while
  const std::vector<BenchLog> logs = readBenchLogs(args.logs, read_options);
  fitting::BenchFit result = fitting::fitBenchModel(logs, options);
  // Thrust against the measured rpm, for the ESC telemetry's view (when the logs have rpm).
  if (std::any_of(logs.begin(), logs.end(), [](const BenchLog& log) { return log.has(BenchColumn::kRpm); })) {
    try {
      const RpmThrust rpm_thrust = fitRpmThrust(logs, result.model.metadata().benchAirDensity());
      result.model.setRpmThrust(rpm_thrust);
      std::printf("thrust from rpm: T = %.4g n^2 %c %.4g n N (n in rpm), rms %.3g N over %d rows\n",
                  rpm_thrust.n_per_rpm2, rpm_thrust.n_per_rpm < 0.0 ? '-' : '+', std::abs(rpm_thrust.n_per_rpm),
                  rpm_thrust.rms_n, rpm_thrust.rows);
    } catch (const DataError& e) {
      std::printf("note: %s\n", e.what());
    }
  }
  // What the estimator will do with the file, done before anything is written: a model the loader
  // refuses is never left on disk, nor reported as written.
  std::string yaml;
  if (result.validation_error.empty()) {
    yaml = modelToYaml(result.model, "Response surfaces fitted by fit_surfaces from " + std::to_string(logs.size()) +
                                         " bench logs; fit quality per output under 'fit'.");
    try {
      parseModelYaml(yaml, args.out);
    } catch (const ConfigError& e) {
      std::fprintf(stderr, "fit_surfaces: the fitted model would not load and was not written: %s\n", e.what());
      return 1;
    }
  }
  for (const std::string& note : result.notes) std::printf("note: %s\n", note.c_str());
  std::printf("cross-validation: %s\n", result.grouping_description.c_str());
  printSummary(result);
  if (result.validation_error.empty()) {
    const std::filesystem::path folder = std::filesystem::path(args.out).parent_path();
    if (!folder.empty()) std::filesystem::create_directories(folder);
    writeTextFile(args.out, yaml);
  }

  if (!args.report.empty()) {
    std::filesystem::create_directories(args.report);
    fitting::writeFitReportData(result, args.report);
    args.plotter.plot("fit", args.report);
    const std::string markdown_path = args.report + "/fit_report.md";
    writeTextFile(markdown_path, fitting::fitReportMarkdown(result, result.validation_error.empty() ? args.out : ""));
    std::printf("report: %s\n", markdown_path.c_str());
  }
  if (!result.validation_error.empty()) {
    std::fprintf(stderr, "fit_surfaces: the fitted model fails the loader's check and was not written: %s\n",
                 result.validation_error.c_str());
    return 1;
  }
  std::printf("model: %s\n", args.out.c_str());
  return 0;
}

}  // namespace

int runFitSurfaces(int argc, char** argv) {
  CLI::App app{
      "Fits the response surfaces of one ESC-motor-propeller combination to thrust-stand logs (native CSV or "
      "Tyto/RCbenchmark exports) and writes the model file estimator_node loads."};
  Arguments args;
  fitting::FitOptions options;
  BenchLogOptions log_options;
  app.add_option("logs", args.logs, "Bench logs, or directories of *.csv logs")->required();
  app.add_option("--out", args.out, "Model file to write (YAML)")->required()->check(fileToWrite());
  app.add_option("--report", args.report, "Directory for the report (Markdown, CSV data, PNG figures)")
      ->check(folderToWrite());
  app.add_option("--group-by", args.group_by,
                 "Cross-validation groups: auto (voltage levels if 3 or more, else PWM levels), voltage, pwm, log")
      ->check(CLI::IsMember({"auto", "voltage", "pwm", "log"}))
      ->capture_default_str();
  app.add_option("--max-pwm-degree", options.max_pwm_degree, "Highest PWM degree tried")
      ->check(wholeNumberIn(1, 5))
      ->capture_default_str();
  app.add_option("--max-voltage-degree", options.max_voltage_degree, "Highest voltage degree tried")
      ->check(wholeNumberIn(0, 3))
      ->capture_default_str();
  app.add_option("--efficiency", args.efficiency,
                 "derived (thrust / power) or surface (fitted to thrust / power samples)")
      ->check(CLI::IsMember({"derived", "surface"}))
      ->capture_default_str();
  // One output per --without: the logs may follow it.
  app.add_option("--without", args.without, "Leave an output out of the model: current, power, rpm (repeatable)")
      ->check(CLI::IsMember({"current", "power", "rpm"}))
      ->allow_extra_args(false);
  app.add_option("--outside", args.outside, "What the model does outside its domain: clamp, extrapolate, reject")
      ->check(CLI::IsMember({"clamp", "extrapolate", "reject"}))
      ->capture_default_str();
  app.add_option("--esc", options.esc, "ESC name (else the logs' '# esc:' line)");
  app.add_option("--motor", options.motor, "Motor name (else '# motor:')");
  app.add_option("--propeller", options.propeller, "Propeller name (else '# propeller:')");
  app.add_option("--air-temperature-c", options.air_temperature_c,
                 "Bench air temperature, deg C (else '# air_temperature_c:' or an ambient_temp_c column)");
  app.add_option("--air-pressure-pa", options.air_pressure_pa,
                 "Bench air pressure, Pa (else '# air_pressure_pa:' or a pressure_pa column)");
  app.add_option("--supply", args.supply, "regulated or battery (else '# supply:')")
      ->check(CLI::IsMember({"regulated", "battery"}));
  app.add_option("--steady-voltage-mad", options.levels.steady_voltage_mad_v,
                 "A log is one voltage level when the median absolute deviation of its voltage is at most this (V)")
      ->check(positiveNumber())
      ->capture_default_str();
  app.add_option("--voltage-bin", options.levels.voltage_bin_v,
                 "Voltage bin width for logs whose voltage wanders, e.g. battery discharges (V)")
      ->check(positiveNumber())
      ->capture_default_str();
  log_options.addTo(app);
  args.plotter.addTo(app);
  return runToolCommand("fit_surfaces", app, argc, argv, [&] { return fit(args, options, log_options.readOptions()); });
}

}  // namespace propulsion_estimator
