#include "propulsion_estimator/sim/stand/bench_simulator.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/simulation_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/sim/physics/lipo_battery.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/sim/physics/power_train.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace sim {
namespace {

constexpr double kStepS = 0.02;             // integration step; the rotor lag is ~0.07 s
constexpr double kControlIntervalS = 0.1;   // HX711 at its 10 Hz output rate
constexpr double kThrustSettleS = 10.0;     // constant-thrust runs are logged once the controller has settled
constexpr double kMaxRunS = 12.0 * 3600.0;  // a discharge that has not reached the cut-off by then never will
// A sweep of more pulse widths than this is a typing error (5 us steps over 800-2200 us are 281).
constexpr double kMaxSweepPulseWidths = 1e6;
// A constant thrust this many load-cell sigmas beyond what the PWM range gives is unreachable.
constexpr double kUnreachableThrustSigmas = 3.0;

// Pulse widths of one sweep (validated: at most kMaxSweepPulseWidths).
double sweepPulseWidthCount(const BenchExperiment& experiment) {
  return std::floor((experiment.pwm_end_us - experiment.pwm_start_us) / experiment.pwm_step_us + 1e-9) + 1.0;
}

// Logs rows as the bench's sensors see them and, optionally, as they are.
class Recorder {
 public:
  Recorder(const BenchSensors& sensors, std::uint64_t seed, BenchLog* measured, BenchLog* truth)
      : sensors_(sensors), rng_(seed), measured_(measured), truth_(truth) {}

  // The voltage the bench's sensor reads now; the row logged next uses this reading.
  double readVoltage(double terminal_voltage_v) {
    voltage_reading_ = sensors_.voltage_v.measure(terminal_voltage_v, rng_);
    return voltage_reading_;
  }
  double readThrust(double thrust_n) { return sensors_.thrust_n.measure(thrust_n, rng_); }

  void row(double time_s, double pwm_us, int run, const PowerTrainState& state, double air_c) {
    const ChainState& motor = state.motors[0];
    const double current = sensors_.current_a.measure(state.current_a, rng_);
    add(measured_,
        {time_s, pwm_us, voltage_reading_, readThrust(motor.thrust_n), current, voltage_reading_ * current,
         sensors_.rpm.measure(motor.rpm(), rng_), sensors_.temperature_c.measure(air_c, rng_),
         sensors_.temperature_c.measure(state.winding_temperature_c[0], rng_)},
        run);
    if (truth_) {
      add(truth_,
          {time_s, pwm_us, state.terminal_voltage_v, motor.thrust_n, state.current_a,
           state.terminal_voltage_v * state.current_a, motor.rpm(), air_c, state.winding_temperature_c[0]},
          run);
    }
  }

 private:
  static void add(BenchLog* log, const std::vector<double>& values, int run) {
    static const BenchColumn kColumns[] = {BenchColumn::kTime,   BenchColumn::kPwm,         BenchColumn::kVoltage,
                                           BenchColumn::kThrust, BenchColumn::kCurrent,     BenchColumn::kPower,
                                           BenchColumn::kRpm,    BenchColumn::kAmbientTemp, BenchColumn::kMotorTemp};
    for (std::size_t i = 0; i < values.size(); ++i) log->column(kColumns[i]).push_back(values[i]);
    log->extra_columns["run"].push_back(std::to_string(run));
    log->line_numbers.push_back(0);
  }

  const BenchSensors& sensors_;
  std::mt19937_64 rng_;
  double voltage_reading_ = 0.0;
  BenchLog* measured_;
  BenchLog* truth_;
};

std::vector<double> sweepPulseWidths(const BenchExperiment& experiment) {
  const long count = static_cast<long>(sweepPulseWidthCount(experiment));
  std::vector<double> pwms;
  for (long i = 0; i < count; ++i) pwms.push_back(experiment.pwm_start_us + i * experiment.pwm_step_us);
  return pwms;
}

// Refuses a constant thrust the bench cannot hold within its PWM range from the run's full
// battery: more than the top pulse width gives, or less than the bottom one does.
void checkThrustReachable(const SimParams& params, const SimEffects& effects, const BenchExperiment& experiment,
                          const AirConditions& air, double target_n, const std::string& what) {
  const PowerTrain train(PropulsionChain(params.chain), 1, effects, air.temperature_c);
  const LipoBattery battery(params.battery, experiment.initial_soc);
  const double series_ohm = battery.seriesResistanceOhm() + effects.supply_resistance_ohm.value_or(0.0);
  const auto thrustAt = [&](double pwm_us) {
    const ChainInput input{params.chain.esc.duty(pwm_us), 0.0, air.densityKgM3(), train.electricalTemperatureC(0)};
    return train.chain().steadyFromSource(input, battery.sourceVoltage(), series_ohm, 1, nullptr).thrust_n;
  };
  const double margin = kUnreachableThrustSigmas * params.bench.sensors.thrust_n.effectiveSigma();
  const auto grams = [](double newtons) { return formatPrintf("%.0f", newtons / kNewtonPerGramForce); };
  const double highest = thrustAt(params.bench.sweep_pwm_max_us);
  if (target_n > highest + margin) {
    throw ConfigError(what + ": only " + grams(highest) + " g at " + formatNumber(params.bench.sweep_pwm_max_us) +
                      " us");
  }
  const double lowest = thrustAt(params.bench.sweep_pwm_min_us);
  if (target_n < lowest - margin) {
    throw ConfigError(what + ": already " + grams(lowest) + " g at " + formatNumber(params.bench.sweep_pwm_min_us) +
                      " us");
  }
}

void runSweeps(const SimParams& params, const SimEffects& effects, const BenchExperiment& experiment,
               const AirConditions& air, Recorder* recorder) {
  const long steps = std::max(1L, std::lround(experiment.step_duration_s / kStepS));
  const double dt = experiment.step_duration_s / steps;
  double time = 0.0;
  for (std::size_t run = 0; run < experiment.voltages_v.size(); ++run) {
    PowerTrain train(PropulsionChain(params.chain), 1, effects, air.temperature_c);
    const Supply supply{experiment.voltages_v[run], 0.0};
    for (double pwm : sweepPulseWidths(experiment)) {
      const std::vector<double> pwms{pwm};
      for (long i = 0; i < steps; ++i) train.step(pwms, supply, air, dt);
      time += experiment.step_duration_s;
      const PowerTrainState& state = train.step(pwms, supply, air, 0.0);
      recorder->readVoltage(state.terminal_voltage_v);
      recorder->row(time, pwm, static_cast<int>(run) + 1, state, air.temperature_c);
    }
  }
}

// One run on a freshly charged battery, logged every sample interval (from `log_after_s` on)
// until the measured voltage falls below the cut-off. `controller`, when given, sets the pulse
// width from the load cell's reading at the HX711's rate.
void runOnBattery(const SimParams& params, const SimEffects& effects, const BenchExperiment& experiment,
                  const AirConditions& air, int run, double initial_pwm_us, double log_after_s,
                  const std::function<double(double thrust_reading_n, double pwm_us)>& controller,
                  const std::string& what, double* time, Recorder* recorder) {
  PowerTrain train(PropulsionChain(params.chain), 1, effects, air.temperature_c);
  LipoBattery battery(params.battery, experiment.initial_soc);
  std::vector<double> pwms{initial_pwm_us};
  const long control_steps = std::lround(kControlIntervalS / kStepS);
  const long sample_steps = std::max(1L, std::lround(experiment.sample_interval_s / kStepS));
  long step = 0;
  for (;; ++step) {
    const double t = step * kStepS;
    if (t > kMaxRunS) {
      throw SimulationError(what + " did not reach the " + formatNumber(experiment.cutoff_voltage_v) +
                            " V cut-off in " + formatNumber(kMaxRunS / 3600.0) + " h");
    }
    // The state at t; the call then advances the rotor and the windings to t + step.
    const PowerTrainState& state =
        train.step(pwms, Supply{battery.sourceVoltage(), battery.seriesResistanceOhm()}, air, kStepS);
    if (step > 0 && step % sample_steps == 0 && t >= log_after_s) {
      if (recorder->readVoltage(state.terminal_voltage_v) < experiment.cutoff_voltage_v) break;
      recorder->row(*time + t, pwms[0], run, state, air.temperature_c);
    }
    if (controller && step > 0 && step % control_steps == 0) {
      pwms[0] = controller(recorder->readThrust(state.motors[0].thrust_n), pwms[0]);
    }
    battery.draw(state.current_a, kStepS);
    if (battery.stateOfCharge() <= 0.0) {
      throw SimulationError(what + " emptied the battery before the measured voltage fell below the " +
                            formatNumber(experiment.cutoff_voltage_v) + " V cut-off");
    }
  }
  *time += step * kStepS;
}

}  // namespace

const char* benchExperimentName(BenchExperimentKind kind) {
  switch (kind) {
    case BenchExperimentKind::kPwmSweep: return "pwm_sweep";
    case BenchExperimentKind::kDischarge: return "discharge";
    case BenchExperimentKind::kConstantThrust: return "constant_thrust";
  }
  return "?";
}

void BenchExperiment::validate() const {
  // From one integration step to an hour.
  requireWithin("sample_interval_s", sample_interval_s, kStepS, 3600.0, " s");
  requirePositive("cutoff_voltage_v", cutoff_voltage_v);
  requirePositive("initial_soc", initial_soc, 1.0);
  switch (kind) {
    case BenchExperimentKind::kPwmSweep:
      if (voltages_v.empty()) throw FieldError("voltages_v", "no supply voltage to sweep at");
      for (double voltage : voltages_v) requirePositive("voltages_v", voltage, 60.0, " V");
      if (!(pwm_start_us >= 800.0 && pwm_end_us <= 2200.0 && pwm_start_us < pwm_end_us)) {
        throw FieldError("pwm_start_us", "[" + formatNumber(pwm_start_us) + ", " + formatNumber(pwm_end_us) +
                                             "] is not a range within 800..2200 us");
      }
      requirePositive("pwm_step_us", pwm_step_us);
      if (sweepPulseWidthCount(*this) > kMaxSweepPulseWidths) {
        throw FieldError("pwm_step_us", formatNumber(pwm_step_us) + " gives " +
                                            formatNumber(sweepPulseWidthCount(*this)) + " pulse widths from " +
                                            formatNumber(pwm_start_us) + " to " + formatNumber(pwm_end_us) +
                                            " us (at most " + formatNumber(kMaxSweepPulseWidths) + ")");
      }
      requireWithin("step_duration_s", step_duration_s, kStepS, 3600.0, " s");
      break;
    case BenchExperimentKind::kDischarge:
      if (pwms_us.empty()) throw FieldError("pwms_us", "no pulse width to discharge at");
      for (double pwm : pwms_us) requireWithin("pwms_us", pwm, 800.0, 2200.0, " us");
      break;
    case BenchExperimentKind::kConstantThrust:
      if (thrusts_n.empty()) throw FieldError("thrusts_n", "no thrust to hold");
      for (double thrust : thrusts_n) requirePositive("thrusts_n", thrust);
      requirePositive("thrust_gain_us_per_n_s", thrust_gain_us_per_n_s);
      break;
  }
}

BenchExperiment thesisBenchExperiment(BenchExperimentKind kind, const SimParams& params) {
  BenchExperiment experiment;
  experiment.kind = kind;
  switch (kind) {
    case BenchExperimentKind::kPwmSweep:
      for (int i = 0; i <= 7; ++i) experiment.voltages_v.push_back(10.5 + 0.3 * i);
      experiment.pwm_start_us = params.bench.sweep_pwm_min_us;
      experiment.pwm_end_us = params.bench.sweep_pwm_max_us;
      experiment.pwm_step_us = 5.0;
      break;
    case BenchExperimentKind::kDischarge:
      for (double pwm : {1600.0, 1700.0, 1800.0, 1900.0}) {
        if (pwm >= params.bench.sweep_pwm_min_us && pwm <= params.bench.sweep_pwm_max_us)
          experiment.pwms_us.push_back(pwm);
      }
      break;
    case BenchExperimentKind::kConstantThrust:
      for (double grams : {300.0, 350.0, 400.0, 450.0, 500.0})
        experiment.thrusts_n.push_back(grams * kNewtonPerGramForce);
      break;
  }
  return experiment;
}

BenchLog simulateBench(const SimParams& params, const SimEffects& all_effects, const BenchExperiment& experiment,
                       std::uint64_t seed, BenchLog* truth) {
  params.validate();
  all_effects.validate();
  experiment.validate();
  const SimEffects effects = all_effects.onTheBench();
  const AirConditions air = effects.air.value_or(params.bench.air);
  BenchLog log;
  if (truth) *truth = BenchLog{};
  Recorder recorder(params.bench.sensors, seed, &log, truth);
  double time = 0.0;
  switch (experiment.kind) {
    case BenchExperimentKind::kPwmSweep: runSweeps(params, effects, experiment, air, &recorder); break;
    case BenchExperimentKind::kDischarge:
      for (std::size_t run = 0; run < experiment.pwms_us.size(); ++run) {
        const double pwm = experiment.pwms_us[run];
        runOnBattery(params, effects, experiment, air, static_cast<int>(run) + 1, pwm, 0.0, nullptr,
                     "discharge at " + formatNumber(pwm) + " us", &time, &recorder);
      }
      break;
    case BenchExperimentKind::kConstantThrust:
      for (std::size_t run = 0; run < experiment.thrusts_n.size(); ++run) {
        const double target = experiment.thrusts_n[run];
        // Grams to six digits: 2000 g, not its round trip through newtons (1999.9999999999998).
        const std::string what = "constant thrust of " + formatPrintf("%.6g", target / kNewtonPerGramForce) + " g";
        checkThrustReachable(params, effects, experiment, air, target, what);
        const double lo = params.bench.sweep_pwm_min_us;
        const double hi = params.bench.sweep_pwm_max_us;
        const auto controller = [&](double reading, double pwm) {
          return std::clamp(pwm + experiment.thrust_gain_us_per_n_s * (target - reading) * kControlIntervalS, lo, hi);
        };
        runOnBattery(params, effects, experiment, air, static_cast<int>(run) + 1, 0.5 * (lo + hi), kThrustSettleS,
                     controller, what, &time, &recorder);
      }
      break;
  }

  const BenchSensors& sensors = params.bench.sensors;
  for (BenchLog* out : {&log, truth}) {
    if (!out) continue;
    out->source = "simulated " + std::string(benchExperimentName(experiment.kind)) + " (" + params.source + ")";
    auto& meta = out->metadata;
    meta["esc"] = params.chain.esc.name;
    meta["motor"] = params.chain.motor.name;
    meta["propeller"] = params.chain.propeller.name;
    const bool battery = experiment.kind != BenchExperimentKind::kPwmSweep;
    meta["supply"] = battery ? "battery" : "regulated";
    if (battery) meta["battery"] = params.battery.name;
    meta["air_temperature_c"] = formatNumber(air.temperature_c);
    meta["air_pressure_pa"] = formatNumber(air.pressure_pa);
    meta["experiment"] = benchExperimentName(experiment.kind);
    meta["effects"] = effects.summary();
    meta["seed"] = std::to_string(seed);
    meta["source"] = "propulsion_estimator simulate bench, parameters " + params.source;
    const double noise_scale = out == truth ? 0.0 : 1.0;
    const std::pair<const char*, const SensorNoise*> noise[] = {{"thrust_n", &sensors.thrust_n},
                                                                {"current_a", &sensors.current_a},
                                                                {"voltage_v", &sensors.voltage_v},
                                                                {"rpm", &sensors.rpm},
                                                                {"temperature_c", &sensors.temperature_c}};
    for (const auto& [name, sensor] : noise) {
      meta[std::string("noise_sigma_") + name] = formatNumber(noise_scale * sensor->sigma);
      meta[std::string("resolution_") + name] = formatNumber(noise_scale * sensor->resolution);
    }
    // Rows sit below the metadata lines and the header of the native CSV.
    for (std::size_t i = 0; i < out->line_numbers.size(); ++i)
      out->line_numbers[i] = static_cast<int>(meta.size() + 2 + i);
  }
  return log;
}

}  // namespace sim
}  // namespace propulsion_estimator
