#include "simulate_command.h"

#include <rosbag/exceptions.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>

#include "propulsion_estimator/sim/stand/bench_simulator.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/logs/flight_manifest.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/dataflash_flight_sink.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/flight/ulog_flight_sink.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/sim/physics/sim_effects_yaml.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "propulsion_estimator/bag/bag_flight_sink.h"
#include "propulsion_estimator/logs/bench_csv.h"
#include "tool_command.h"

namespace propulsion_estimator {
namespace {

struct BenchOptions {
  std::string params;
  std::string effects;
  std::string experiment;
  std::vector<double> voltages_v;
  std::vector<double> pwm_range_us;
  double pwm_step_us = 0.0;
  double step_duration_s = 0.0;
  std::vector<double> pwms_us;
  std::vector<double> thrusts_g;
  double sample_interval_s = 0.0;
  double cutoff_v = 0.0;
  std::uint64_t seed = 1;
  std::string output;
  std::string truth;
};

struct FlightOptions {
  std::string params;
  std::string profile;
  std::string effects;
  std::uint64_t seed = 1;
  std::string bag;
  std::string manifest;
  std::string compression = "none";
  std::string log_format = "bag";
  std::string ulog_layout = "px4-1.12";
};

sim::SimEffects loadEffects(const std::string& path) {
  return path.empty() ? sim::SimEffects{} : sim::loadSimEffectsFile(path);
}

// The command-line option behind each field of BenchExperiment, for refusals.
std::string optionOf(const std::string& field) {
  static const std::map<std::string, std::string> kOptions = {{"voltages_v", "--voltage"},
                                                              {"pwm_start_us", "--pwm-range"},
                                                              {"pwm_step_us", "--pwm-step"},
                                                              {"step_duration_s", "--step-duration"},
                                                              {"pwms_us", "--pwm"},
                                                              {"thrusts_n", "--thrust-g"},
                                                              {"sample_interval_s", "--sample-interval"},
                                                              {"cutoff_voltage_v", "--cutoff-v"}};
  const auto found = kOptions.find(field);
  return found == kOptions.end() ? field : found->second;
}

void runBench(const BenchOptions& options) {
  const sim::SimParams params = sim::loadSimParamsFile(options.params);
  const sim::SimEffects effects = loadEffects(options.effects);
  const sim::BenchExperimentKind kind = options.experiment == "pwm_sweep"   ? sim::BenchExperimentKind::kPwmSweep
                                        : options.experiment == "discharge" ? sim::BenchExperimentKind::kDischarge
                                                                            : sim::BenchExperimentKind::kConstantThrust;
  sim::BenchExperiment experiment = sim::thesisBenchExperiment(kind, params);
  if (!options.voltages_v.empty()) experiment.voltages_v = options.voltages_v;
  if (!options.pwm_range_us.empty()) {
    experiment.pwm_start_us = options.pwm_range_us[0];
    experiment.pwm_end_us = options.pwm_range_us[1];
  }
  if (options.pwm_step_us > 0.0) experiment.pwm_step_us = options.pwm_step_us;
  if (options.step_duration_s > 0.0) experiment.step_duration_s = options.step_duration_s;
  if (!options.pwms_us.empty()) experiment.pwms_us = options.pwms_us;
  if (!options.thrusts_g.empty()) {
    experiment.thrusts_n.clear();
    for (double grams : options.thrusts_g) experiment.thrusts_n.push_back(grams * kNewtonPerGramForce);
  }
  if (options.sample_interval_s > 0.0) experiment.sample_interval_s = options.sample_interval_s;
  if (options.cutoff_v > 0.0) experiment.cutoff_voltage_v = options.cutoff_v;
  try {
    experiment.validate();
  } catch (const FieldError& e) {
    throw ConfigError(optionOf(e.field()) + ": " + e.problem());
  }
  BenchLog truth;
  const BenchLog log =
      sim::simulateBench(params, effects, experiment, options.seed, options.truth.empty() ? nullptr : &truth);
  saveNativeBenchCsv(log, options.output);
  if (!options.truth.empty()) saveNativeBenchCsv(truth, options.truth);
  std::cout << "simulate bench: " << log.rows() << " rows of " << sim::benchExperimentName(kind) << " -> "
            << options.output << "\n";
}

void runFlight(const FlightOptions& options) {
  const sim::SimParams params = sim::loadSimParamsFile(options.params);
  const sim::FlightProfile profile = sim::loadFlightProfileFile(options.profile);
  const sim::SimEffects effects = loadEffects(options.effects);
  const Vehicle vehicle = loadVehicleUrdf(profile.vehicle.urdf_path);
  const rosbag::compression::CompressionType compression = options.compression == "bz2" ? rosbag::compression::BZ2
                                                           : options.compression == "lz4"
                                                               ? rosbag::compression::LZ4
                                                               : rosbag::compression::Uncompressed;
  // The refusals that need no flying come before any file is touched; the bag is written under
  // another name and takes its own only when the flight has been flown to its end.
  sim::checkFlight(params, effects, profile, vehicle);
  const std::string active = options.bag + ".active";
  sim::FlightResult result;
  const auto remove_active = [&] {
    std::error_code ignored;
    std::filesystem::remove(active, ignored);
  };
  try {
    if (options.log_format == "ulog") {
      // PX4 1.12's layout by default: actuator_outputs in us, as the other formats log them; the
      // newer one logs actuator_motors (normalised), read through --pwm-range-us.
      const sim::UlogLayout layout =
          options.ulog_layout == "px4-1.14" ? sim::UlogLayout::kPx4v1_14 : sim::UlogLayout::kPx4v1_12;
      sim::UlogFlightSink sink(layout, profile.autopilot.pwm_min_us, profile.autopilot.pwm_max_us);
      result = sim::simulateFlight(params, effects, profile, vehicle, options.seed, &sink);
      sink.save(active);
    } else if (options.log_format == "dataflash") {
      sim::DataflashFlightSink sink;
      result = sim::simulateFlight(params, effects, profile, vehicle, options.seed, &sink);
      sink.save(active);
    } else {
      BagFlightSink sink(active, compression);
      result = sim::simulateFlight(params, effects, profile, vehicle, options.seed, &sink);
      sink.close();
    }
  } catch (const rosbag::BagException& e) {
    remove_active();
    throw InputError(options.bag + ": " + e.what());
  } catch (...) {
    remove_active();
    throw;
  }
  std::error_code error;
  std::filesystem::rename(active, options.bag, error);
  if (error) throw InputError(options.bag + ": cannot move " + active + " there: " + error.message());
  std::cout << "simulate flight: " << formatNumber(result.duration_s) << " s, battery from "
            << formatNumber(100.0 * profile.vehicle.battery_initial_soc) << " % to "
            << formatNumber(std::round(100.0 * result.final_state_of_charge)) << " % -> " << options.bag << "\n";
  if (options.manifest.empty()) return;
  const std::filesystem::path folder = std::filesystem::absolute(options.manifest).parent_path();
  FlightManifest manifest;
  manifest.flights.push_back(
      {std::filesystem::proximate(std::filesystem::absolute(options.bag), folder).string(), result.segments, {}});
  const bool airborne = profile.manifest_spans == sim::ManifestSpans::kAirborne;
  const std::string settle = formatNumber(profile.manifest_settle_s);
  saveFlightManifest(manifest, options.manifest,
                     "Simulated by: simulate flight --params " + options.params + " --profile " + options.profile +
                         (options.effects.empty() ? "" : " --effects " + options.effects) + " --seed " +
                         std::to_string(options.seed) + "\nEffects: " + effects.summary() +
                         (airborne ? "\nAirborne segments from " + settle +
                                         " s after each lift-off to 0.2 m above touchdown"
                                   : "\nHover segments from " + settle + " s after each hover starts") +
                         "; times in seconds from the bag's first message.");
  std::cout << "simulate flight: " << result.segments.size() << (airborne ? " airborne" : " hover") << " segments -> "
            << options.manifest << "\n";
}

}  // namespace

int runSimulateCommand(int argc, char** argv) {
  CLI::App app{"Physics simulator of the ESC-motor-propeller chain: thrust-stand logs and hover-flight bags."};
  app.require_subcommand(1);

  BenchOptions bench;
  CLI::App* bench_command =
      app.add_subcommand("bench", "Simulated thrust-stand experiments (thesis chapter 4) -> native bench CSV");
  bench_command->add_option("--params", bench.params, "Simulator parameter file (config/sim/*.yaml)")->required();
  bench_command->add_option("--effects", bench.effects, "Effects file (default: no effects)");
  bench_command
      ->add_option("--experiment", bench.experiment, "pwm_sweep (4.1), discharge (4.2) or constant_thrust (4.3)")
      ->required()
      ->check(CLI::IsMember({"pwm_sweep", "discharge", "constant_thrust"}));
  bench_command->add_option("--voltage", bench.voltages_v, "pwm_sweep: supply voltages (default 10.5, 10.8, ..., 12.6)")
      ->check(numberIn(1.0, 60.0));
  bench_command
      ->add_option("--pwm-range", bench.pwm_range_us,
                   "pwm_sweep: first and last pulse width, us (default: the parameter file's)")
      ->expected(2)
      ->check(numberIn(800.0, 2200.0));
  bench_command->add_option("--pwm-step", bench.pwm_step_us, "pwm_sweep: step, us (default 5)")
      ->check(positiveNumber());
  bench_command->add_option("--step-duration", bench.step_duration_s, "pwm_sweep: dwell per step, s (default 1)")
      ->check(positiveNumber());
  bench_command
      ->add_option("--pwm", bench.pwms_us, "discharge: pulse widths, us (default 1600 1700 1800 1900 within the range)")
      ->check(numberIn(800.0, 2200.0));
  bench_command->add_option("--thrust-g", bench.thrusts_g, "constant_thrust: thrusts, g (default 300 350 400 450 500)")
      ->check(positiveNumber());
  bench_command
      ->add_option("--sample-interval", bench.sample_interval_s,
                   "discharge, constant_thrust: log interval, s (default 1)")
      ->check(positiveNumber());
  bench_command->add_option("--cutoff-v", bench.cutoff_v, "discharge, constant_thrust: cut-off voltage (default 10.5)")
      ->check(positiveNumber());
  bench_command->add_option("--seed", bench.seed, "Seed of the sensor noise (default 1)");
  bench_command->add_option("--output", bench.output, "Native bench CSV to write")->required()->check(fileToWrite());
  bench_command->add_option("--truth", bench.truth, "Also write the noise-free log to this CSV")->check(fileToWrite());

  FlightOptions flight;
  CLI::App* flight_command =
      app.add_subcommand("flight", "Simulated hover flight -> rosbag with MAVROS topics (or a ULog, a DataFlash log), and its manifest");
  flight_command->add_option("--params", flight.params, "Simulator parameter file (config/sim/*.yaml)")->required();
  flight_command->add_option("--profile", flight.profile, "Flight profile (config/sim/*_flight.yaml)")->required();
  flight_command->add_option("--effects", flight.effects, "Effects file (default: no effects)");
  flight_command->add_option("--seed", flight.seed, "Seed of the sensor noise (default 1)");
  flight_command->add_option("--log,--bag", flight.bag, "Log to write (--bag, its old name)")->required();
  flight_command
      ->add_option("--log-format", flight.log_format,
                   "bag (default: MAVROS topics and /sim/truth), ulog (PX4) or dataflash (ArduPilot .bin); the same "
                   "flight in each")
      ->check(CLI::IsMember({"bag", "ulog", "dataflash"}));
  CLI::Option* ulog_layout =
      flight_command
          ->add_option("--ulog-layout", flight.ulog_layout,
                       "With --log-format ulog: px4-1.12 (default: actuator_outputs in us, sensor_combined) or "
                       "px4-1.14 (actuator_motors normalised 0..1 only, vehicle_acceleration; diagnose_gap then "
                       "needs --pwm-range-us, the profile's pwm_min_us and pwm_max_us)")
          ->check(CLI::IsMember({"px4-1.12", "px4-1.14"}));
  flight_command->add_option("--manifest", flight.manifest,
                             "Manifest to write (hover or airborne segments with their true masses)");
  flight_command->add_option("--compression", flight.compression, "Bag compression: none (default), bz2 or lz4")
      ->check(CLI::IsMember({"none", "bz2", "lz4"}));

  return runToolCommand("simulate", app, argc, argv, [&] {
    if (bench_command->parsed()) runBench(bench);
    if (ulog_layout->count() > 0 && flight.log_format != "ulog") {
      throw ConfigError("--ulog-layout: " + flight.ulog_layout + " is for --log-format ulog, not " + flight.log_format);
    }
    if (flight_command->parsed()) runFlight(flight);
    return 0;
  });
}

}  // namespace propulsion_estimator
