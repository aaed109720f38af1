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
  int motors = 4;
  int cells = 0;
  double capacity_mah = 0.0;
  double usable_fraction = 0.8;
  double cell_full_v = 4.2;
  double cell_cutoff_v = 3.5;
  int steps = 200;  ///< integration steps over the usable charge

  double fullVoltage() const { return cells * cell_full_v; }
  double cutoffVoltage() const { return cells * cell_cutoff_v; }
  double midVoltage() const { return 0.5 * (fullVoltage() + cutoffVoltage()); }
  double thrustPerMotorN() const;
  BatteryPack pack() const;
  void validate() const;  ///< ConfigError naming the option
};

/// Options of compare_models: the comparison voltage in V, the curves' sampling, and the vehicle
/// for hover and endurance.
struct ComparisonOptions {
  std::optional<double> voltage_v;  ///< where the chapter 7 maxima are taken; default: each model's top
  int curve_points = 701;           ///< PWM samples over each model's domain
  std::optional<HoverOptions> hover;

  void validate() const;  ///< ConfigError naming the option
};

/// One model's output at one PWM, in the units of thesis chapter 7 (g, A, W, g/W, rpm); NaN for
/// an output the model does not have.
struct ComparisonSample {
  double pwm_us = 0.0;
  double voltage_v = 0.0;
  double thrust_g = 0.0;
  double current_a = 0.0;
  double power_w = 0.0;
  double efficiency_g_per_w = 0.0;
  double rpm = 0.0;
};

/// The chapter 7 row of one combination, its hover point and endurance.
struct ModelComparison {
  std::string label;
  ModelMetadata metadata;
  double voltage_v = 0.0;  ///< where the row's values are: --voltage, or the domain bound it was clamped to
  std::vector<std::string> notes;        ///< on the chapter 7 row (a --voltage outside the domain)
  std::vector<ComparisonSample> curve;  ///< the model against PWM at voltage_v
  double max_thrust_g = 0.0;
  double max_current_a = 0.0;
  double max_power_w = 0.0;
  double max_rpm = 0.0;
  double efficiency_at_max_power_g_per_w = 0.0;
  double peak_efficiency_g_per_w = 0.0;  ///< over samples drawing >= kEfficiencyMinPowerShare of max power
  double peak_efficiency_pwm_us = 0.0;
  std::optional<double> max_motor_temp_c;     ///< from the logs, where logged
  std::vector<ComparisonSample> logged_near;  ///< log rows within kNearVoltageV of voltage_v
  std::optional<HoverPoint> hover;            ///< at the battery's mid-discharge voltage
  std::vector<DischargeStep> discharge;  ///< integrateHoverDischarge's, from the full pack
  std::optional<double> endurance_min;
  std::vector<std::string> hover_notes;
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
