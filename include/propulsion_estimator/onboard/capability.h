#pragma once

#include <optional>
#include <string>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/onboard/health_summary.h"
#include "propulsion_estimator/estimation/motor_health.h"
#include "propulsion_estimator/model/hover_endurance.h"

namespace propulsion_estimator {

/// What the capability answers are computed with (node parameters capability/...; README,
/// "Capability"). The battery is optional as a whole: without capacity and cells the endurance
/// and the cut-off figures are NaN with the reason.
struct CapabilityConfig {
  double rate_hz = 1.0;                ///< Hz; how often ~capability is published
  std::optional<double> pwm_max_us;    ///< us; top of the usable PWM range; default the model's domain maximum
  /// Attitude control needs headroom above the hover thrust: PX4 and ArduPilot practice keeps the
  /// hover throttle near or below half.
  double min_thrust_to_weight = 1.6;
  std::optional<double> capacity_ah;  ///< Ah; the pack's rated capacity
  std::optional<int> cells;           ///< in series
  double usable_fraction = 0.8;       ///< share of the capacity drawn at the cut-off (BatteryPack)
  double cell_full_v = 4.2;           ///< V per cell
  double cell_cutoff_v = 3.5;         ///< V per cell
  double reserve_s = 120.0;           ///< s; hover endurance below this warns
  MotorHealthConfig motor_health;  ///< the motor-health check's settings (capability/motor_health/...)

  /// FieldError naming `capability/<field>`: rate, PWM and thrust-to-weight not positive, a capacity
  /// at or below zero, cells outside 1..14, capacity without cells (or cells without capacity),
  /// usable fraction outside (0, 1], a cut-off at or above the full voltage, a negative reserve.
  void validate() const;
  /// The pack when capacity and cells are configured.
  std::optional<BatteryPack> pack() const;
};

/// What the autopilot reports of the battery besides its voltage (sensor_msgs/BatteryState):
/// remaining share 0..1 and charge in Ah, current drawn in A (its magnitude); NaN when not
/// measured. A percentage outside 0..1 (MAVROS' -1 % "unknown") or a negative charge counts as
/// not measured.
struct BatteryReport {
  double percentage = kNaN;  ///< remaining share of the capacity, 0..1
  double charge_ah = kNaN;  ///< remaining charge, Ah
  double current_a = kNaN;  ///< current drawn, A
};

/// The answers of thesis chapter 1 for the present flight, SI units; NaN where a figure cannot be
/// computed, with the reason in the matching note.
struct CapabilityReport {
  /// The mass the thrust holds in hover (the payload estimator's average) and what it rests on.
  double hover_mass_kg = kNaN;
  std::string hover_basis;  ///< "hovering", "holding the last hover", or why there is no hover mass
  double voltage_v = kNaN;  ///< battery voltage the figures are computed at, V
  double pwm_max_us = kNaN;  ///< the top of the usable PWM range, us
  /// At the present voltage, over all motors at pwm_max_us.
  double max_thrust_n = kNaN;
  double thrust_to_weight = kNaN;  ///< max_thrust_n over the hover weight
  double max_additional_payload_kg = kNaN;  ///< keeping min_thrust_to_weight; negative: over the limit
  /// The same at the pack's cut-off voltage.
  ///@{
  double cutoff_voltage_v = kNaN;
  double max_thrust_at_cutoff_n = kNaN;
  double thrust_to_weight_at_cutoff = kNaN;
  double max_additional_payload_at_cutoff_kg = kNaN;
  ///@}
  std::string payload_note;  ///< why a payload figure is NaN; "" when all are computed
  /// The hover operating point at the present voltage, all motors.
  ///@{
  double hover_pwm_us = kNaN;
  double hover_current_a = kNaN;
  ///@}
  /// The pack's state: share of the capacity left and on what it rests (percentage | charge |
  /// voltage), usable charge left above the cut-off in Ah.
  ///@{
  double state_of_charge = kNaN;
  std::string charge_basis;  ///< what the state of charge rests on: "percentage", "charge" or "voltage"
  double remaining_ah = kNaN;  ///< usable charge left above the cut-off, Ah
  ///@}
  double hover_endurance_s = kNaN;  ///< hover time left until the cut-off voltage, s
  std::string endurance_basis;  ///< how it was computed, or why it is NaN
  bool payload_over_limit = false;  ///< the hover mass exceeds what keeps min_thrust_to_weight
  bool endurance_below_reserve = false;  ///< hover_endurance_s is below CapabilityConfig::reserve_s
};

/// Computes the capability answers from the estimator's state (ROS-free; called at
/// CapabilityConfig::rate_hz). The endurance integrates the hover discharge
/// (integrateHoverDischarge, as compare_models does) from the pack's present state to its cut-off.
class CapabilityEstimator {
 public:
  /// Throws FieldError for a bad config, or a pwm_max_us at or below the model's lowest PWM. `model`
  /// must outlive the estimator (the Estimator's own).
  CapabilityEstimator(const PropulsionModel& model, int motors, CapabilityConfig config);

  /// The answers for the estimator's last output and the battery's report; never throws.
  CapabilityReport evaluate(const EstimatorOutput& output, const BatteryReport& battery) const;

  /// As validated.
  const CapabilityConfig& config() const { return config_; }

 private:
  /// Thrust of all motors at the top PWM and `voltage_v`; NaN when the model rejects it.
  double maxThrustN(double voltage_v) const;
  void evaluateEndurance(const BatteryReport& battery, CapabilityReport* c) const;

  const PropulsionModel& model_;
  int motors_;
  CapabilityConfig config_;
  double pwm_max_us_;
};

/// The Capability diagnostic: WARN when the payload exceeds its limit, the hover endurance is below
/// the reserve or a motor is flagged (each named with its figures), OK otherwise, with the figures
/// and the centre-of-gravity offset as values.
HealthStatus judgeCapability(const CapabilityReport& capability, const MotorHealthVerdict& health,
                             const CapabilityConfig& config);

}  // namespace propulsion_estimator
