#include "diagnose_gap_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/mavros_topics.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/parallel_for.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/gap/airborne_stretch.h"
#include "propulsion_estimator/gap/diagnosis.h"
#include "propulsion_estimator/gap/gap_report.h"
#include "propulsion_estimator/gap/model_check_replay.h"
#include "propulsion_estimator/gap/motor_balance.h"
#include "propulsion_estimator/gap/motor_health_replay.h"
#include "propulsion_estimator/logs/bench_log_reader.h"
#include "propulsion_estimator/logs/flight_manifest.h"
#include "propulsion_estimator/logs/flight_streams.h"
#include "propulsion_estimator/model/effect_description.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "flight_input_options.h"
#include "flight_log_formats.h"
#include "report_plotter.h"
#include "tool_command.h"

namespace propulsion_estimator {
namespace {

struct Arguments {
  std::string model;
  std::string manifest;
  std::string reference;
  std::string out;
  FlightInputOptions input;
  std::vector<std::string> bench;
  double rotor_diameter_m = gap::DiagnosisConfig{}.rotor_diameter_m;
  double rotor_time_constant_s = kNaN;  // NaN: identified from the flights
  gap::PartsSpread parts_spread;
  gap::AirborneSettings airborne;  // for flights weighed as a whole (manifest mass_kg)
  bool no_rpm_view = false;
  int jobs = 1;
  ReportPlotter plotter;
  std::string command;  // as given, for the report
};

// A flight of the manifest, read, or refused with one line.
struct FlightRead {
  std::optional<Flight> flight;
  std::string refusal;
  std::string stretches;  // a flight weighed as a whole: the airborne stretches found
  bool reads_named_sources = false;  // FlightLogReader::readsNamedSources(): a rosbag's topics
};

// A flight given `mass_kg:` for its airborne stretches: its segments, found in its log.
std::string weighAirborne(const PropulsionModel& model, const ManifestFlight& entry,
                          const gap::AirborneSettings& settings, Flight* flight) {
  std::vector<gap::AirborneStretch> found;
  flight->segments = gap::airborneSegments(flight->streams, model, entry.airborne_mass_kg, settings, &found);
  std::string text;
  for (std::size_t k = 0; k < found.size(); ++k) {
    text += (k ? "; " : "") + formatPrintf("lift-off %.1f s", found[k].lift_off_s) +
            formatPrintf(", touchdown %.1f s", found[k].touchdown_s) + formatPrintf(", weighed %.1f", found[k].start_s) +
            formatPrintf("-%.1f s", found[k].end_s) + formatPrintf(" at %.3f kg", flight->segments[k].mass_kg);
  }
  return "airborne stretches found: " + text;
}

// Where the report says an untestable effect's signals come from: a bag's topics (those read, not
// the defaults), and another format's signal names, as its reading notes list them
// ("static_pressure: not in this log (no vehicle_air_data)"). `bags` and `others`: how many
// flights of each were read.
effects::SignalSources signalSources(const FlightLogOptions& options, int bags, int others) {
  const auto source = [&](const std::string& name, const std::string& usual) {
    const auto given = options.sources.find(name);
    const std::string topic = given == options.sources.end() ? usual : given->second;
    if (others == 0) return topic;
    return "the log's " + name + (bags == 0 ? "" : " (a bag's " + topic + ")");
  };
  effects::SignalSources sources;
  sources.battery = source("battery", kBatteryTopic);
  sources.velocity = source("velocity", kVelocityTopic);
  sources.imu = source("imu", kImuTopic);
  for (input::Scalar scalar : input::kAllScalars) {
    sources.inputs[input::index(scalar)] = source(input::spec(scalar).name, input::spec(scalar).topic);
  }
  return sources;
}

// The signal sources are set once the flights are read (signalSources).
gap::DiagnosisConfig configOf(const Arguments& args) {
  gap::DiagnosisConfig config;
  config.rotor_diameter_m = args.rotor_diameter_m;
  config.rotor_time_constant_s = args.rotor_time_constant_s;
  config.rpm_view = !args.no_rpm_view;
  config.parts_spread = args.parts_spread;
  try {
    config.validate();
  } catch (const FieldError& e) {
    // Only the settings given as options can be refused: name the option ("rotor_diameter_m" -> --rotor-diameter-m).
    std::string option = "--" + e.field();
    std::replace(option.begin(), option.end(), '_', '-');
    throw ConfigError(option + ": " + e.problem());
  }
  return config;
}

FlightRead readFlight(const std::string& manifest, std::size_t index, const ManifestEntry& entry,
                      const FlightLogOptions& options, const PropulsionModel& model,
                      const gap::AirborneSettings& airborne) {
  if (!entry.refusal.empty()) return {std::nullopt, entry.refusal, {}, false};
  const std::string at = manifest + ": flights[" + std::to_string(index) + "]";
  try {
    const std::unique_ptr<FlightLogReader> reader =
        flightLogFormats().open(resolveLogPath(manifest, entry.flight.log));
    const std::vector<ManifestSegment>& segments = entry.flight.segments;
    // The log's end as printed (to the millisecond): a segment that ends there is the log's span
    // as its user reads it.
    const double printed_end_s = reader->durationS() + 0.0005;
    for (std::size_t s = 0; s < segments.size(); ++s) {
      if (segments[s].end_s > printed_end_s) {
        return {std::nullopt, at + ".segments[" + std::to_string(s) + "]: " + formatNumber(segments[s].start_s) +
                                  ".." + formatNumber(segments[s].end_s) + " s is outside " + reader->path() +
                                  " (0.." + formatPrintf("%.3f", reader->durationS()) + " s)",
                {}, false};
      }
    }
    Flight flight{entry.flight.log, reader->read(options), segments, ""};
    // Known once read() has run.
    flight.damage = reader->refusal();
    const std::string stretches =
        entry.flight.airborne_mass_kg.empty() ? "" : weighAirborne(model, entry.flight, airborne, &flight);
    return {std::move(flight), "", stretches, reader->readsNamedSources()};
  } catch (const InputError& e) {
    return {std::nullopt, at + ": " + e.what(), {}, false};
  }
}

// Reads the flights on `jobs` threads; the results in manifest order.
std::vector<FlightRead> readFlights(const std::string& manifest, const std::vector<ManifestEntry>& entries,
                                    const FlightLogOptions& options, const PropulsionModel& model,
                                    const gap::AirborneSettings& airborne, int jobs) {
  std::vector<FlightRead> reads(entries.size());
  parallelFor(entries.size(), jobs,
              [&](std::size_t i) { reads[i] = readFlight(manifest, i, entries[i], options, model, airborne); });
  return reads;
}

// "rc_out 90115, battery 1803, ..., no rangefinder, ...": the readings of each signal.
std::string streamSummary(const FlightStreams& streams, std::size_t* readings) {
  const std::vector<std::size_t> counts = signalCounts(streams);
  std::vector<std::string> items;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const std::string& name = flightSignalNames()[i];
    items.push_back(counts[i] == 0 ? "no " + name : name + " " + std::to_string(counts[i]));
    *readings += counts[i];
  }
  return joined(items);
}

// The motor balance's verdict in one line of the terminal's summary (report.md has its table).
std::string motorVerdictLine(const gap::MotorBalance& motors) {
  if (!motors.unavailable.empty()) return "motors: not judged: " + motors.unavailable;
  if (!motors.suspect_channel) return "motors: no motor stands out";
  const auto gap = std::find_if(motors.motors.begin(), motors.motors.end(),
                                [&](const gap::MotorGap& m) { return m.channel == *motors.suspect_channel; });
  return "suspect motor: channel " + std::to_string(*motors.suspect_channel) + ", modelled " +
         (gap == motors.motors.end() ? std::string("n/a")
                                     : formatPrintf("%.1f", gap->thrust_gap_pct) + " +- " + formatPrintf("%.1f", gap->ci_pct)) +
         " % above its share against " + gap::motorBasisAgainst(motors.basis) + "; it gives " +
         formatPrintf("%.1f", 100.0 * motors.suspect_thrust_factor, "n/a") + " % of its modelled thrust";
}

// The diagnosis of the flights read, and its report in `out`: report.md, report.yaml, the
// figures and their data. The flights refused are listed among what could not be used.
void diagnoseAndReport(const Arguments& args, const PropulsionModel& model, const Vehicle& vehicle,
                       const std::vector<Flight>& flights, const gap::DiagnosisConfig& config,
                       const std::vector<BenchLog>& bench, const std::vector<std::string>& refusals) {
  gap::Diagnosis diagnosis = gap::diagnoseGap(model, vehicle, flights, config, bench);
  // What the diagnosis could not use or doubts reaches the terminal too (the refusals already did);
  // the shortfall of steady data has a line of its own below.
  for (const std::string& problem : diagnosis.problems) {
    if (problem != diagnosis.steady_data_shortfall) std::printf("problem: %s\n", problem.c_str());
  }
  diagnosis.problems.insert(diagnosis.problems.begin(), refusals.begin(), refusals.end());
  writeTextFile(args.out + "/report.yaml", gap::gapReportYaml(diagnosis));
  gap::writeGapReportData(diagnosis, args.out);
  args.plotter.plot("gap", args.out);
  writeTextFile(args.out + "/report.md", gap::gapReportMarkdown(diagnosis, model, args.command));
  // The input model with the selected effects: what estimator_node loads to correct online.
  std::vector<std::string> selected;
  for (effects::Kind kind : diagnosis.selected) selected.push_back(effects::kindName(kind));
  std::vector<std::string> corrected_with = selected;
  for (const gap::Ambiguity& ambiguity : diagnosis.ambiguous) {
    corrected_with.push_back(std::string(effects::kindName(ambiguity.kinds[0])) + " (ambiguous, the best fit of its group)");
  }
  // The fingerprint the motors were judged against goes with it: the node's live check and later
  // diagnoses judge change from the same reference.
  // The healthy level is folded into the corrected model's thrust_loss: its reference keeps the
  // fingerprint but not the level, which was measured against the uncorrected model.
  PropulsionModel corrected = model.withEffects(gap::correctedEffects(diagnosis));
  std::optional<MotorReference> reference = config.motor_reference;
  if (reference) reference->thrust_factor = reference->current_thrust_factor = reference->rpm_thrust_factor = kNaN;
  corrected.setMotorReference(reference);
  // The healthy level folded into thrust_loss is no selected effect: the header says where it is from.
  saveModelFile(corrected, args.out + "/corrected_model.yaml",
                args.model + " with the effects diagnose_gap selected (" +
                    (corrected_with.empty() ? std::string("none") : joined(corrected_with)) + ")" +
                    (gap::foldsHealthyLevel(diagnosis)
                         ? " and the vehicle's level on its healthy flights, " +
                               formatPrintf("%.4f", diagnosis.motors.reference_thrust_factor) +
                               " of the model's thrust, in thrust_loss"
                         : std::string("")) +
                    "; see report.md");

  const gap::ResidualStats& overall = diagnosis.overall;
  std::printf("gap: %d samples, model minus flight: bias %s %%, RMSE %s %%\n", overall.samples,
              formatPrintf("%.2f", overall.bias_pct).c_str(), formatPrintf("%.2f", overall.rmse_pct).c_str());
  if (!diagnosis.steady_data_shortfall.empty()) std::printf("%s\n", diagnosis.steady_data_shortfall.c_str());
  std::printf("selected: %s; held-out RMSE %s %% -> %s %%\n", selected.empty() ? "none" : joined(selected).c_str(),
              formatPrintf("%.2f", diagnosis.heldout.before_rmse_pct).c_str(),
              formatPrintf("%.2f", diagnosis.heldout.after_rmse_pct).c_str());
  for (const gap::Ambiguity& ambiguity : diagnosis.ambiguous) {
    std::string group;
    for (effects::Kind kind : ambiguity.kinds) group += (group.empty() ? "" : " or ") + std::string(effects::kindName(kind));
    std::printf("ambiguous: %s (the correction uses %s); %s\n", group.c_str(), effects::kindName(ambiguity.kinds[0]),
                ambiguity.separating_flight.c_str());
  }
  std::printf("%s\n", motorVerdictLine(diagnosis.motors).c_str());
  if (diagnosis.heldout.nested.unavailable.empty()) {
    std::printf("nested held-out RMSE (flights that chose nothing) %s %% -> %s %%\n",
                formatPrintf("%.2f", diagnosis.heldout.nested.before_rmse_pct).c_str(),
                formatPrintf("%.2f", diagnosis.heldout.nested.after_rmse_pct).c_str());
  }
  std::printf("report: %s/report.md, corrected model: %s/corrected_model.yaml\n", args.out.c_str(), args.out.c_str());

  // What the node's onboard check would have said of the same flights, with the same model and the
  // reference the motors were judged against (as the node would with corrected_model.yaml).
  PropulsionModel onboard_model = model;
  onboard_model.setMotorReference(config.motor_reference);
  std::vector<std::string> names;
  std::vector<gap::MotorHealthReplay> replays;
  int flagged = 0, judged = 0;
  for (const Flight& flight : flights) {
    names.push_back(flight.name);
    replays.push_back(gap::replayMotorHealth(onboard_model, vehicle, flight.streams));
    flagged += !replays.back().flagged_channels.empty();
    judged += replays.back().judgements > 0;
  }
  writeTextFile(args.out + "/motor_health.yaml", gap::motorHealthReplayYaml(names, replays));
  // A flight never judged is not a healthy one: the count says how many were.
  std::printf("onboard motor-health check: judged on %d of %zu flights, a motor flagged on %d%s; %s/motor_health.yaml\n",
              judged, flights.size(), flagged,
              judged < static_cast<int>(flights.size())
                  ? " (not judged: no steady hover the node's check accepts at its default parameters)"
                  : "",
              args.out.c_str());
  std::vector<gap::ModelCheckReplay> checks;
  int with_telemetry = 0, checked_flagged = 0;
  for (const Flight& flight : flights) {
    checks.push_back(gap::replayModelCheck(onboard_model, vehicle, flight.streams));
    with_telemetry += checks.back().telemetry;
    checked_flagged += !checks.back().verdicts.empty();
  }
  writeTextFile(args.out + "/model_check.yaml", gap::modelCheckReplayYaml(names, checks));
  std::printf("live model check of ESC telemetry: %d of %d flights with telemetry flagged; %s/model_check.yaml\n",
              checked_flagged, with_telemetry, args.out.c_str());
}

// The vehicle's healthy fingerprint from the --reference manifest's flights, and the effects they
// show (the diagnosis names only what changed from them); every flight must read.
MotorReference learnReference(const Arguments& args, const PropulsionModel& model, const Vehicle& vehicle,
                              const FlightLogOptions& options, const gap::DiagnosisConfig& config,
                              gap::ReferenceEffects* reference_effects) {
  std::vector<Flight> flights;
  for (FlightRead& read : readFlights(args.reference, loadFlightManifestEntries(args.reference), options, model, args.airborne, args.jobs)) {
    if (!read.flight) throw ConfigError("--reference: " + read.refusal);
    flights.push_back(std::move(*read.flight));
  }
  MotorReference reference = gap::learnReference(model, vehicle, flights, config);
  gap::DiagnosisConfig own = config;
  own.motor_reference = reference;
  *reference_effects = gap::fitReferenceEffects(model, vehicle, flights, own);
  std::vector<std::string> shares;
  for (std::size_t k = 0; k < reference.shares.size(); ++k) {
    shares.push_back(formatPrintf("%.1f", 100.0 * reference.shares[k]) + " +- " +
                     formatPrintf("%.1f", 100.0 * reference.share_std[k]));
  }
  std::printf("reference: %d healthy flights; each motor's share of the thrust in steady hover, %%: %s\n",
              reference.flights, joined(shares).c_str());
  std::vector<std::string> shown;
  for (const auto& [kind, effect] : *reference_effects) {
    shown.push_back(std::string(effects::describe(kind).name) + " " + formatPrintf("%.4g", effect.value) + " +- " +
                    formatPrintf("%.2g", effect.ci_half) +
                    (std::isfinite(effect.signal_low) ? " (" + formatPrintf("%.4g", effect.signal_low) + ".." +
                                                            formatPrintf("%.4g", effect.signal_high) + ")"
                                                      : std::string()));
  }
  std::printf("reference: each effect fitted on them beside the day's air (an effect as large here is not named): %s\n",
              shown.empty() ? "none (no effect the flights can test)" : joined(shown).c_str());
  return reference;
}

int diagnose(const Arguments& args) {
  const PropulsionModel model = loadModelFile(args.model);
  const Vehicle vehicle = args.input.vehicle("diagnose_gap");
  const FlightLogOptions options =
      args.input.logOptions(static_cast<int>(vehicle.rotors.size()));
  gap::DiagnosisConfig config = configOf(args);
  if (!args.reference.empty()) {
    config.motor_reference = learnReference(args, model, vehicle, options, config, &config.reference_effects);
  } else if (model.motorReference()) {
    config.motor_reference = model.motorReference();
    if (config.motor_reference->shares.size() != vehicle.rotors.size()) {
      throw ConfigError(args.model + ": motor_reference: " + std::to_string(config.motor_reference->shares.size()) +
                        " shares for the vehicle's " + std::to_string(vehicle.rotors.size()) + " rotors");
    }
    std::printf("reference: the model file's, from %d healthy flights\n", model.motorReference()->flights);
  }
  const std::vector<ManifestEntry> entries = loadFlightManifestEntries(args.manifest);
  std::vector<BenchLog> bench;
  for (const std::string& path : args.bench) bench.push_back(readBenchLog(path));
  // What would stop the report comes before the long read.
  args.plotter.check();
  std::filesystem::create_directories(args.out);

  const auto started = std::chrono::steady_clock::now();
  std::vector<FlightRead> reads =
      readFlights(args.manifest, entries, options, model, args.airborne, args.jobs);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  std::vector<Flight> flights;
  std::vector<std::string> refusals;
  std::vector<std::string> damages;
  std::size_t readings = 0;
  int bags = 0;
  for (FlightRead& read : reads) {
    if (!read.flight) {
      std::fprintf(stderr, "diagnose_gap: %s\n", read.refusal.c_str());
      refusals.push_back(read.refusal);
      continue;
    }
    if (!read.flight->damage.empty()) {
      const std::string problem = read.flight->damage + " (the flight is read up to there)";
      std::fprintf(stderr, "diagnose_gap: %s\n", problem.c_str());
      damages.push_back(problem);
    }
    std::printf("read %s: %s\n", read.flight->streams.source.c_str(),
                streamSummary(read.flight->streams, &readings).c_str());
    for (const std::string& note : read.flight->streams.notes) std::printf("  %s\n", note.c_str());
    if (!read.stretches.empty()) std::printf("  %s\n", read.stretches.c_str());
    flights.push_back(std::move(*read.flight));
    bags += read.reads_named_sources;
  }
  std::printf("read %zu of %zu flights, %zu readings, in %s s with %d jobs\n", flights.size(), reads.size(), readings,
              formatPrintf("%.2f", seconds).c_str(), args.jobs);

  config.signal_sources = signalSources(options, bags, static_cast<int>(flights.size()) - bags);
  std::vector<std::string> problems = refusals;
  problems.insert(problems.end(), damages.begin(), damages.end());
  if (!flights.empty()) diagnoseAndReport(args, model, vehicle, flights, config, bench, problems);
  if (refusals.empty()) return 0;
  std::fprintf(stderr, "diagnose_gap: %zu of %zu flights refused\n", refusals.size(), reads.size());
  return 1;
}

}  // namespace

int runDiagnoseGap(int argc, char** argv) {
  CLI::App app{
      "Diagnoses the gap between a propulsion model and weighed flights: reads each flight's log (a rosbag's MAVROS topics, a PX4 ULog, an ArduPilot DataFlash log, a Crazyflie uSD log) "
      "and the manifest's segments of known mass."};
  Arguments args;
  app.add_option("--model", args.model, "Model file (YAML), as estimator_node loads it")->required();
  app.add_option("--manifest", args.manifest, "Flight manifest: logs and their weighed segments (YAML)")->required();
  app.add_option("--out", args.out, "Directory for the report")->required()->check(folderToWrite());
  app.add_option("--reference", args.reference,
                 "Flight manifest of the same vehicle's flights known to be healthy (e.g. after maintenance): each "
                 "motor is judged by its change from them (needs --urdf or --frame)");
  args.input.addTo(app);
  app.add_option("--bench", args.bench,
                 "Bench log measured under other conditions than the model's (another day, a battery, a warm motor): "
                 "its load cell is the truth (repeatable)");
  app.add_option("--rotor-diameter-m", args.rotor_diameter_m, "Rotor diameter (ground effect within two diameters)")
      ->capture_default_str();
  app.add_option("--rotor-time-constant-s", args.rotor_time_constant_s,
                 "The rotors' spin-up lag, s (0..1; a bench step response's time constant; 0: none); without it "
                 "the lag is identified from the flights");
  app.add_option("--parts-thrust-spread", args.parts_spread.thrust_fraction,
                 "How far a healthy vehicle's rotors' mean thrust may differ from the bench unit's (fraction, 0..0.5): "
                 "an effect must change the thrust by more to be named")
      ->capture_default_str();
  app.add_option("--parts-esc-spread-us", args.parts_spread.esc_end_point_us,
                 "How far a healthy vehicle's ESC end points may differ from the bench ESC's, us (0..100); likewise")
      ->capture_default_str();
  app.add_option("--parts-max-imitated-share", args.parts_spread.max_imitated_share,
                 "An effect reading a signal is named, however small, when those two spreads could imitate at most "
                 "this share of its change over the blocks (0..1): a shape no part gives")
      ->capture_default_str();
  app.add_option("--airborne-settle-s", args.airborne.settle_s,
                 "A flight weighed as a whole (manifest mass_kg): seconds after lift-off left out of its weighed stretch")
      ->check(numberIn(0.0, 60.0))
      ->capture_default_str();
  app.add_option("--airborne-min-s", args.airborne.min_weighed_s,
                 "A flight weighed as a whole: its shortest weighed stretch, s (shorter airborne stretches are hops)")
      ->check(numberIn(0.5, 3600.0))
      ->capture_default_str();
  app.add_flag("--no-rpm-view", args.no_rpm_view,
               "Leave ESC telemetry's rotor speeds out of the diagnosis (the RPM view): the PWM and current views only");
  app.add_option("--jobs", args.jobs, "Logs read in parallel")->check(wholeNumberIn(1, 64))->capture_default_str();
  // Before the required options are checked: a tool or test builds its list of effects from this.
  app.add_flag_callback(
      "--list-effects",
      [] {
        for (const std::string& name : effects::allNames()) std::printf("%s\n", name.c_str());
        throw CLI::Success();
      },
      "Print the names of the effects the diagnosis knows, one per line, and exit");
  args.plotter.addTo(app);
  for (int i = 0; i < argc; ++i) args.command += (i == 0 ? "diagnose_gap" : " " + std::string(argv[i]));
  return runToolCommand("diagnose_gap", app, argc, argv, [&] { return diagnose(args); });
}

}  // namespace propulsion_estimator
