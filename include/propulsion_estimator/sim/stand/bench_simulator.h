#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "propulsion_estimator/logs/bench_log.h"
#include "propulsion_estimator/sim/physics/sim_effects.h"
#include "propulsion_estimator/sim/physics/sim_params.h"

namespace propulsion_estimator {
namespace sim {

/// The thesis' three bench experiments (chapter 4).
enum class BenchExperimentKind {
  kPwmSweep,        ///< 4.1: PWM stepped up at constant voltage, regulated supply, one sweep per voltage
  kDischarge,       ///< 4.2: constant PWM from a full battery down to the cut-off voltage, one run per PWM
  kConstantThrust,  ///< 4.3: thrust held by the bench's controller while the battery discharges, one run per thrust
};
/// "pwm_sweep", "discharge", "constant_thrust".
const char* benchExperimentName(BenchExperimentKind kind);

/// The settings of one bench experiment: the pulse widths (us), voltages (V) or thrusts (N) it runs
/// at, and its timing in s.
struct BenchExperiment {
  BenchExperimentKind kind = BenchExperimentKind::kPwmSweep;  ///< which experiment
  /// pwm_sweep: the supply voltages (V), the pulse widths from start to end in steps (us), the dwell.
  ///@{
  std::vector<double> voltages_v;
  double pwm_start_us = 0.0;
  double pwm_end_us = 0.0;
  double pwm_step_us = 0.0;
  double step_duration_s = 1.0;  ///< dwell at each pulse width; the row is logged at its end
  ///@}
  /// discharge: the constant pulse width of each run, us.
  std::vector<double> pwms_us;
  /// constant_thrust: the thrust each run holds, N.
  std::vector<double> thrusts_n;
  double thrust_gain_us_per_n_s = 80.0;  ///< the bench controller's integral gain on the load cell
  /// discharge and constant_thrust: s between logged rows.
  double sample_interval_s = 1.0;
  double cutoff_voltage_v = 10.5;  ///< a run stops when the measured voltage falls below it
  double initial_soc = 1.0;        ///< each run starts on a battery charged to this

  /// Throws FieldError naming the member (e.g. "pwm_step_us") for an empty or inconsistent setup,
  /// a sweep of more than 1e6 pulse widths, or a dwell or sample interval outside 0.02..3600 s
  /// (one integration step to an hour).
  void validate() const;
};

/// The thesis' settings of each experiment for this combination: sweeps over the parameter file's
/// PWM range in 5 us steps at 10.5, 10.8, ..., 12.6 V (4.1); discharges at 1600, 1700, 1800 and
/// 1900 us, those within the range (4.2); constant thrust at 300, 350, 400, 450 and 500 g (4.3).
BenchExperiment thesisBenchExperiment(BenchExperimentKind kind, const SimParams& params);

/// Runs `experiment` on the simulated thrust stand and returns what its sensors logged: time_s,
/// pwm_us, voltage_v, thrust_n, current_a, power_w (measured voltage times measured current, as
/// the thesis bench computes it), rpm, ambient_temp_c, motor_temp_c, and the extra column "run"
/// (1-based index of the sweep or discharge). Metadata: esc, motor, propeller, battery, supply,
/// air_temperature_c, air_pressure_pa, experiment, effects, seed, source, and each sensor's
/// noise_sigma_* and resolution_*. Runs start with the motor at air temperature. Of `effects` only
/// those a bench shows apply (SimEffects::onTheBench; the metadata lists them). The same seed gives
/// the same log. `truth`, when given, receives the same rows without sensor noise. Throws
/// ConfigError "constant thrust of 2000 g: only 683 g at 1900 us" (or "already ... at" the bottom
/// of the range) for a thrust the PWM range cannot give from the run's charged battery, by more
/// than three load-cell sigmas; SimulationError for a discharge or constant-thrust run that does not
/// reach its cut-off voltage in time or empties the battery before.
BenchLog simulateBench(const SimParams& params, const SimEffects& effects, const BenchExperiment& experiment,
                       std::uint64_t seed, BenchLog* truth = nullptr);

}  // namespace sim
}  // namespace propulsion_estimator
