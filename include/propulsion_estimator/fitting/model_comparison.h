#pragma once

#include <optional>
#include <string>
#include <vector>

#include "propulsion_estimator/logs/bench_log.h"
#include "propulsion_estimator/model/hover_endurance.h"
#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {
namespace fitting {

/// A vehicle and its LiPo battery, for the hover operating point and endurance of a combination
/// (the battery as BatteryPack models it: model/hover_endurance.h).
struct HoverOptions {
  double vehicle_mass_kg = 0.0;  ///< take-off mass, payload included
  int motors = 4;  ///< rotors, each carrying an equal share of the weight
  int cells = 0;  ///< LiPo cells in series
  double capacity_mah = 0.0;  ///< rated capacity, mAh
  double usable_fraction = 0.8;  ///< share of the capacity drawn when the cut-off is reached
  double cell_full_v = 4.2;  ///< V per cell, full
  double cell_cutoff_v = 3.5;  ///< V per cell at the cut-off
  int steps = 200;  ///< integration steps over the usable charge

  /// V, the full pack
  double fullVoltage() const { return cells * cell_full_v; }
  /// V, the pack at its cut-off
  double cutoffVoltage() const { return cells * cell_cutoff_v; }
  /// V, halfway between full and cut-off
  double midVoltage() const { return 0.5 * (fullVoltage() + cutoffVoltage()); }
  double thrustPerMotorN() const;  ///< N, the hover thrust of each motor
  BatteryPack pack() const;  ///< the battery as BatteryPack models it
  void validate() const;  ///< ConfigError naming the option
};

/// Options of compare_models: the comparison voltage in V, the curves' sampling, and the vehicle
/// for hover and endurance.
struct ComparisonOptions {
  std::optional<double> voltage_v;  ///< where the chapter 7 maxima are taken; default: each model's top
  int curve_points = 701;           ///< PWM samples over each model's domain
  std::optional<HoverOptions> hover;  ///< the vehicle for hover and endurance; none: no hover figures

  void validate() const;  ///< ConfigError naming the option
};

/// One model's output at one PWM, in the units of thesis chapter 7 (g, A, W, g/W, rpm); NaN for
/// an output the model does not have.
struct ComparisonSample {
  double pwm_us = 0.0;  ///< us
  double voltage_v = 0.0;  ///< V
  double thrust_g = 0.0;  ///< g
  double current_a = 0.0;  ///< A
  double power_w = 0.0;  ///< W
  double efficiency_g_per_w = 0.0;  ///< g/W
  double rpm = 0.0;  ///< rpm
};

/// The chapter 7 row of one combination, its hover point and endurance.
struct ModelComparison {
  std::string label;  ///< how the tables name the combination
  ModelMetadata metadata;  ///< the model's ESC, motor, propeller and bench
  double voltage_v = 0.0;  ///< where the row's values are: --voltage, or the domain bound it was clamped to
  std::vector<std::string> notes;        ///< on the chapter 7 row (a --voltage outside the domain)
  std::vector<ComparisonSample> curve;  ///< the model against PWM at voltage_v
  double max_thrust_g = 0.0;  ///< g, at the top of the PWM domain
  double max_current_a = 0.0;  ///< A, at the top of the PWM domain
  double max_power_w = 0.0;  ///< W, at the top of the PWM domain
  double max_rpm = 0.0;  ///< rpm, at the top of the PWM domain
  double efficiency_at_max_power_g_per_w = 0.0;  ///< g/W, at the top of the PWM domain
  double peak_efficiency_g_per_w = 0.0;  ///< over samples drawing >= kEfficiencyMinPowerShare of max power
  double peak_efficiency_pwm_us = 0.0;  ///< us where the peak efficiency is
  std::optional<double> max_motor_temp_c;     ///< from the logs, where logged
  std::vector<ComparisonSample> logged_near;  ///< log rows within kNearVoltageV of voltage_v
  std::optional<HoverPoint> hover;            ///< at the battery's mid-discharge voltage
  std::vector<DischargeStep> discharge;  ///< integrateHoverDischarge's, from the full pack
  std::optional<double> endurance_min;  ///< hover time from the full pack to the cut-off, min
  std::vector<std::string> hover_notes;  ///< why a hover figure is missing or what it assumes
};

/// Log rows this close to the comparison voltage are drawn with its curves.
constexpr double kNearVoltageV = 0.3;

/// Evaluates one combination: curve and maxima at the comparison voltage (default: the top of
/// the model's voltage domain), the motor temperature of its logs, and hover and endurance when
/// options.hover is set. A --voltage outside the domain is refused under the reject policy
/// (ConfigError naming `label`), clamped to the domain (voltage_v says where) or extrapolated
/// otherwise, with a note.
ModelComparison compareModel(const std::string& label, const PropulsionModel& model, const std::vector<BenchLog>& logs,
                             const ComparisonOptions& options);

}  // namespace fitting
}  // namespace propulsion_estimator
