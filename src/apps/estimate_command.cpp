#include "estimate_command.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include <CLI/CLI.hpp>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/parallel_for.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/logs/file_pattern.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/offline/estimate_csv.h"
#include "propulsion_estimator/offline/estimate_summary.h"
#include "propulsion_estimator/offline/flight_record.h"
#include "propulsion_estimator/offline/flight_estimate.h"
#include "propulsion_estimator/offline/flight_feed.h"
#include "propulsion_estimator/offline/yaml_parameter_source.h"
#include "propulsion_estimator/onboard/node_parameters.h"
#include "flight_input_options.h"
#include "flight_log_formats.h"
#include "report_plotter.h"
#include "tool_command.h"

namespace propulsion_estimator {
namespace {

struct Arguments {
  std::string model;
  std::vector<std::string> logs;
  std::string out;
  std::string params;
  double empty_mass_kg = kNaN;
  double sample_rate_hz = offline::EstimateOptions{}.sample_rate_hz;
  std::optional<double> disarmed_pwm_max_us;
  int jobs = 1;
  bool no_figures = false;
  bool check = false;  // read and check the inputs, estimate nothing
  FlightInputOptions input;
  ReportPlotter plotter;
};

// One log's outcome: its directory and estimate, or the one line that refused it.
struct LogResult {
  std::string path;
  std::string directory;
  std::optional<offline::FlightEstimate> estimate;
  std::string refusal;
  double seconds = 0.0;
};

// The logs named, a pattern (quoted, so that the shell left it) expanded in sorted order; a name
// that matches nothing is kept, for its reader to refuse.
std::vector<std::string> expandLogs(const std::vector<std::string>& arguments) {
  std::vector<std::string> paths;
  for (const std::string& argument : arguments) {
    const std::vector<std::string> matches = isFilePattern(argument) ? matchingFiles(argument) : std::vector<std::string>{};
    if (matches.empty()) paths.push_back(argument);
    paths.insert(paths.end(), matches.begin(), matches.end());
  }
  return paths;
}

// A directory per log under --out, named for the log's file name without its extension; with it
// ("flight_ulg") when two logs share a stem, and then with its position when they share a name.
std::vector<std::string> outputDirectories(const std::string& out, const std::vector<std::string>& logs) {
  std::vector<std::string> directories;
  std::set<std::string> taken;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const std::filesystem::path file = std::filesystem::path(logs[i]).filename();
    std::string name = file.stem().empty() ? "log" : file.stem().string();
    const bool shared = std::count_if(logs.begin(), logs.end(), [&](const std::string& other) {
                          return std::filesystem::path(other).filename().stem() == file.stem();
                        }) > 1;
    if (shared) {
      name = file.string();
      std::replace(name.begin(), name.end(), '.', '_');
    }
    if (!taken.insert(name).second) name += "_" + std::to_string(i + 1);
    directories.push_back((std::filesystem::path(out) / name).string());
  }
  return directories;
}

// The node's parameters, from --params as a launch file would load them (else the node's
// defaults), read and validated by the node's own reader; the options on top.
offline::EstimateOptions optionsOf(const Arguments& args, const Vehicle& vehicle) {
  // The model and the URDF are the tool's options; the parameters print them as the node would.
  std::map<std::string, std::string> model{{"model", args.model}};
  if (!args.input.urdf().empty()) model["urdf_file"] = args.input.urdf();
  const std::unique_ptr<offline::YamlParameterSource> source =
      args.params.empty() ? std::make_unique<offline::YamlParameterSource>(model)
                          : std::make_unique<offline::YamlParameterSource>(args.params, model);
  const EstimatorNodeParams params = readNodeParameters(*source);
  if (!args.params.empty()) std::printf("%s\n", describeNodeParameters(params).c_str());
  offline::EstimateOptions options;
  options.estimator = params.estimator;
  options.capability = params.capability;
  options.esc_telemetry = params.esc_telemetry;
  // A log's motor k is its output k: channels 1..n, whatever the vehicle's RCOut channels were.
  const EstimatorConfig numbered = offline::replayEstimatorConfig(vehicle);
  if (source->has("motor_channels") && params.estimator.motor_channels != numbered.motor_channels) {
    throw ConfigError(source->where("motor_channels") + ": estimate reads motor k from the log's output k (1.." +
                      std::to_string(numbered.motor_channels.size()) + "); leave it out");
  }
  options.estimator.motor_channels = numbered.motor_channels;
  if (args.disarmed_pwm_max_us) options.estimator.disarmed_pwm_max_us = *args.disarmed_pwm_max_us;
  if (!std::isnan(args.empty_mass_kg)) options.estimator.empty_mass_kg = args.empty_mass_kg;
  options.sample_rate_hz = args.sample_rate_hz;
  try {
    options.validate(vehicle.rotors.size());
  } catch (const FieldError& e) {
    // A setting given as an option is named as the option, one from the parameters as its key.
    const bool option = e.field() == "sample_rate_hz" || (e.field() == "empty_mass_kg" && !std::isnan(args.empty_mass_kg)) ||
                        (e.field() == "disarmed_pwm_max_us" && args.disarmed_pwm_max_us);
    if (!option) throw ConfigError(source->where(e.field()) + ": " + e.problem());
    std::string name = "--" + e.field();
    std::replace(name.begin(), name.end(), '_', '-');
    throw ConfigError(name + ": " + e.problem());
  }
  return options;
}

LogResult estimateLog(const std::string& path, const std::string& directory, const PropulsionModel& model,
                      const Vehicle& vehicle, const FlightLogOptions& log_options,
                      const offline::EstimateOptions& options, const std::string& model_name) {
  LogResult result{path, directory, std::nullopt, "", 0.0};
  const auto started = std::chrono::steady_clock::now();
  try {
    const std::unique_ptr<FlightLogReader> reader = flightLogFormats().open(path);
    offline::FlightEstimate estimate = offline::estimateFlight(model, vehicle, reader->read(log_options), options);
    estimate.log_damage = reader->refusal();
    // Warnings are printed after the log's name: the reader's line names it once.
    if (!estimate.log_damage.empty()) estimate.warnings.push_back(withoutLogPath(estimate.log_damage, path) + " (read up to there)");
    std::filesystem::create_directories(directory);
    writeTextFile(directory + "/estimates.csv", offline::estimateCsv(estimate.samples));
    writeTextFile(directory + "/summary.md", offline::estimateSummaryMarkdown(estimate, model_name, "mass.png"));
    writeTextFile(directory + "/flight.yaml", offline::flightRecordText(offline::flightRecordOf(estimate)));
    result.estimate = std::move(estimate);
  } catch (const InputError& e) {
    result.refusal = e.what();
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

std::string hoverList(const offline::FlightEstimate& estimate) {
  std::vector<std::string> masses;
  for (const offline::HoverEpisode& h : estimate.hovers) {
    if (!std::isnan(h.total_mass_kg)) masses.push_back(formatPrintf("%.3f kg", h.total_mass_kg));
  }
  return std::to_string(estimate.hovers.size()) + (estimate.hovers.size() == 1 ? " hover" : " hovers") +
         (masses.empty() ? "" : " (" + joined(masses) + ")");
}

// The run's index: every log with its hovers and warnings, or why it was refused.
std::string indexMarkdown(const std::vector<LogResult>& results, const std::string& model) {
  std::string text = "# Estimates\n\nModel: `" + model + "`.\n\n| log | result | warnings |\n|---|---|---|\n";
  for (const LogResult& r : results) {
    const std::string name = std::filesystem::path(r.directory).filename().string();
    if (!r.estimate) {
      text += "| " + r.path + " | refused: " + r.refusal + " | |\n";
      continue;
    }
    text += "| [" + r.path + "](" + name + "/summary.md) | " + hoverList(*r.estimate) + " | " +
            std::to_string(r.estimate->warnings.size()) + " |\n";
  }
  return text;
}

// Runs every log on `jobs` threads, printing a line as each finishes; results in the order given.
std::vector<LogResult> estimateLogs(const Arguments& args, const std::vector<std::string>& logs,
                                    const PropulsionModel& model, const Vehicle& vehicle) {
  const FlightLogOptions log_options = args.input.logOptions(static_cast<int>(vehicle.rotors.size()));
  const offline::EstimateOptions options = optionsOf(args, vehicle);
  const std::vector<std::string> directories = outputDirectories(args.out, logs);
  std::vector<LogResult> results(logs.size());
  std::atomic<std::size_t> done{0};
  parallelFor(logs.size(), args.jobs, [&](std::size_t i) {
    results[i] = estimateLog(logs[i], directories[i], model, vehicle, log_options, options, args.model);
    const LogResult& r = results[i];
    const std::size_t warnings = r.estimate ? r.estimate->warnings.size() : 0;
    const std::string what = r.estimate ? hoverList(*r.estimate) + ", " + std::to_string(warnings) +
                                              (warnings == 1 ? " warning -> " : " warnings -> ") + r.directory
                                        : "refused: " + r.refusal;
    std::printf("[%zu/%zu] %s: %s (%.2f s)\n", ++done, logs.size(), r.path.c_str(), what.c_str(), r.seconds);
    std::fflush(stdout);
  });
  return results;
}

int estimate(const Arguments& args) {
  // Required unless --check, which reads no log: said before any file is read.
  if (!args.check && args.logs.empty()) throw UsageError("logs: at least one flight log is required (or --check)");
  if (!args.check && args.out.empty()) throw UsageError("--out is required (or --check)");
  const PropulsionModel model = loadModelFile(args.model);
  const Vehicle vehicle = args.input.vehicle("estimate");
  if (args.check) {
    args.input.logOptions(static_cast<int>(vehicle.rotors.size()));
    offline::checkEstimateInputs(model, vehicle, optionsOf(args, vehicle));
    std::printf("estimate: --check: %s, the vehicle and %s accepted\n", args.model.c_str(),
                args.params.empty() ? "the node's default parameters" : args.params.c_str());
    return 0;
  }
  const std::vector<std::string> logs = expandLogs(args.logs);
  if (!args.no_figures) args.plotter.check();
  std::filesystem::create_directories(args.out);
  const std::vector<LogResult> results = estimateLogs(args, logs, model, vehicle);
  writeTextFile(args.out + "/summary.md", indexMarkdown(results, args.model));
  std::size_t refused = 0;
  for (const LogResult& r : results) {
    if (!r.estimate) {
      std::fprintf(stderr, "estimate: %s\n", r.refusal.c_str());
      ++refused;
      continue;
    }
    for (const std::string& warning : r.estimate->warnings) std::printf("  %s: %s\n", r.path.c_str(), warning.c_str());
    if (!args.no_figures) args.plotter.plot("estimate", r.directory);
  }
  std::printf("estimated %zu of %zu logs; %s/summary.md\n", results.size() - refused, results.size(),
              args.out.c_str());
  return refused == 0 ? 0 : 1;
}

}  // namespace

int runEstimate(int argc, char** argv) {
  CLI::App app{
      "Runs the estimator's onboard session (hover detection, mass, payload, motor health, capability) offline on "
      "flight logs (PX4 ULog, ArduPilot DataFlash, Crazyflie uSD, rosbag with MAVROS topics), message by message as estimator_node "
      "runs on a replayed bag, and writes per log estimates.csv, summary.md, flight.yaml and mass.png."};
  Arguments args;
  app.add_option("--model", args.model, "Model file (YAML), as estimator_node loads it")->required();
  CLI::Option* logs =
      app.add_option("logs", args.logs, "Flight logs (a quoted pattern such as 'logs/*.ulg' is expanded); required unless --check");
  CLI::Option* out = app.add_option("--out", args.out,
                                    "Directory for the results: one folder per log and summary.md; required unless --check")
                         ->check(folderToWrite());
  app.add_option("--empty-mass-kg", args.empty_mass_kg,
                 "The vehicle's empty mass, kg, for the payload (default: the URDF's inertials, else unknown)");
  app.add_option("--sample-rate-hz", args.sample_rate_hz,
                 "Rows of estimates.csv per second of flight (0: every RCOut message); hovers are judged on every "
                 "message")
      ->capture_default_str();
  app.add_option("--params", args.params,
                 "estimator_node's parameters as a launch file loads them (config/estimator_params.yaml's keys: "
                 "hover/..., payload/..., capability/...); default: the node's defaults");
  app.add_option("--disarmed-pwm-max-us", args.disarmed_pwm_max_us,
                 "PWM at or below this is a disarmed or stopped motor (default the node's, 950 us; ArduPilot: 1000)");
  app.add_option("--jobs", args.jobs, "Logs estimated in parallel")->check(wholeNumberIn(1, 64))->capture_default_str();
  app.add_flag("--no-figures", args.no_figures, "Write no mass.png (no matplotlib needed)");
  app.add_flag("--check", args.check,
               "Read and check --model, the vehicle (--urdf or --frame), --params and the log options as an estimate "
               "would, print the parameters given, and estimate nothing (no logs or --out then): exit 0 when all are "
               "accepted")
      ->excludes(logs)
      ->excludes(out);
  args.input.addTo(app);
  args.plotter.addTo(app);
  return runToolCommand("estimate", app, argc, argv, [&] { return estimate(args); });
}

}  // namespace propulsion_estimator
