#pragma once

#include <optional>
#include <string>
#include <vector>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/onboard/health_summary.h"
#include "propulsion_estimator/estimation/motor_health.h"
#include "propulsion_estimator/model/hover_endurance.h"
#include "propulsion_estimator/onboard/battery_estimator.h"
#include "propulsion_estimator/onboard/ocv_curve.h"
#include "propulsion_estimator/onboard/pack_file.h"
#include "propulsion_estimator/onboard/pack_learner.h"

namespace propulsion_estimator {

/// How BatteryState.percentage is read (capability/battery/percentage): `ignore` (the default:
/// its meaning differs between autopilots), `px4_remaining` (PX4's remaining, already to the
/// autopilot's own empty voltage: the endurance runs until it is drawn, no cut-off subtracted
/// again) or `capacity_fraction` (a share of the rated capacity, e.g. a smart battery's: a
/// measurement of the state of charge).
enum class PercentageMode { kIgnore, kPx4Remaining, kCapacityFraction };
/// "ignore", "px4_remaining", "capacity_fraction".
const char* percentageModeName(PercentageMode mode);
/// The mode named `name`; throws FieldError("capability/battery/percentage") for another name.
PercentageMode percentageModeFromName(const std::string& name);

/// What the capability answers are computed with (node parameters capability/...;
/// docs/capability.md). The battery is optional as a whole: without capacity and cells the endurance
/// and the cut-off figures are NaN with the reason. The user gives what is printed on the pack
/// (cells, capacity) and the loaded cut-off; the rest is estimated in flight.
struct CapabilityConfig {
  double rate_hz = 1.0;              ///< Hz; how often ~capability is published
  std::optional<double> pwm_max_us;  ///< us; top of the usable PWM range; default the model's domain maximum
  /// Attitude control needs headroom above the hover thrust: PX4 and ArduPilot practice keeps the
  /// hover throttle near or below half.
  double min_thrust_to_weight = 1.6;
  std::optional<double> capacity_ah;  ///< Ah; the pack's rated capacity
  std::optional<int> cells;           ///< in series
  std::string chemistry = "lipo";     ///< the built-in open-circuit curve: lipo | li_ion
  /// The user's open-circuit curve (capability/battery/ocv_table/soc, cell_v); replaces the
  /// chemistry's when given.
  ///@{
  std::vector<double> ocv_table_soc, ocv_table_cell_v;
  ///@}
  double cell_cutoff_v = 3.5;  ///< V per cell; the loaded terminal voltage the endurance runs to
  PercentageMode percentage = PercentageMode::kIgnore;  ///< how BatteryState.percentage is read
  double reserve_s = 120.0;  ///< s; hover endurance below this warns
  /// deg C; the pack's temperature when BatteryState does not report one (capability/battery/
  /// temperature_c); not set: unknown, and the interval allows for a cold pack.
  std::optional<double> temperature_c;
  MotorHealthConfig motor_health;  ///< the motor-health check's settings (capability/motor_health/...)
  /// What the pack file holds of the pack flown (capability/battery/pack_file): its learned
  /// capacity, curve (over the charge flown; the chemistry's or the user's beyond) and resistance
  /// replace the rated capacity, the curve and the resistance's empty start. nullopt: none.
  std::optional<PackRecord> pack;

  /// Throws FieldError naming the parameter (capability/...): rate, PWM and thrust-to-weight not positive, a
  /// capacity at or below zero, cells outside 1..14, capacity without cells (or cells without
  /// capacity), an unknown chemistry or a bad ocv_table, a cut-off outside the curve's voltages,
  /// a negative reserve.
  void validate() const;
  /// The cells' open-circuit curve: the user's table, else the chemistry's.
  OcvCurve curve() const;
  /// The battery estimator's configuration when capacity and cells are configured, with what the
  /// pack file learned.
  std::optional<BatteryEstimatorConfig> battery() const;
};

/// What the autopilot reports of the battery besides its voltage (sensor_msgs/BatteryState):
/// percentage 0..1 (read per CapabilityConfig::percentage) and the current drawn in A (its
/// magnitude); NaN when not measured. A percentage outside 0..1 (MAVROS' -1 "unknown") counts as
/// not measured.
struct BatteryReport {
  double percentage = kNaN;  ///< 0..1, read per CapabilityConfig::percentage
  double current_a = kNaN;   ///< A; current drawn (its magnitude)
  double temperature_c = kNaN;  ///< deg C; the pack's (BatteryState.temperature), NaN when not reported
};

/// The answers of thesis chapter 1 for the present flight, SI units; NaN where a figure cannot be
/// computed, with the reason in the matching note.
struct CapabilityReport {
  /// The mass the thrust holds in hover (the payload estimator's average) and what it rests on.
  double hover_mass_kg = kNaN;
  std::string hover_basis;  ///< "10.0 s of hover (hovering)" or "no hover yet"
  double voltage_v = kNaN;  ///< V; the battery voltage now
  double pwm_max_us = kNaN;  ///< us; the top of the usable PWM range
  /// All motors at pwm_max_us through the corrected model, at the voltage the pack sags to at
  /// that current (full_throttle_voltage_v, full_throttle_current_a).
  double max_thrust_n = kNaN;
  double thrust_to_weight = kNaN;  ///< max_thrust_n over the hover weight
  double max_additional_payload_kg = kNaN;  ///< keeping min_thrust_to_weight; negative: over the limit
  double full_throttle_voltage_v = kNaN;  ///< V; the terminals at full throttle
  double full_throttle_current_a = kNaN;  ///< A; all motors at full throttle
  /// Whether full_throttle_voltage_v is the voltage the pack sags to (a converged battery
  /// estimate); false: the voltage measured now, an optimistic limit, and the diagnostic's status
  /// says "at the present voltage, no sag".
  bool payload_sagged = false;
  /// The same with the pack's terminals at the cut-off voltage.
  ///@{
  double cutoff_voltage_v = kNaN;
  double max_thrust_at_cutoff_n = kNaN;
  double thrust_to_weight_at_cutoff = kNaN;
  double max_additional_payload_at_cutoff_kg = kNaN;
  ///@}
  std::string payload_note;  ///< why a payload figure is NaN or on what it rests; "" when all are computed
  /// The hover operating point at the present voltage, all motors, through the corrected model.
  ///@{
  double hover_pwm_us = kNaN;
  double hover_current_a = kNaN;
  ///@}
  /// A; the battery current the model's motors do not account for (avionics, companion computer,
  /// camera, and the model's own current error): the measured less the modelled, averaged while
  /// the motors run; drawn with the hover in the endurance. NaN without a measured current.
  double unmodelled_current_a = kNaN;
  /// The pack's state (BatteryEstimator) and on what it rests.
  double state_of_charge = kNaN;  ///< 0..1 of the rated capacity
  double state_of_charge_std = kNaN;  ///< one standard deviation, the curve's uncertainty included
  double internal_resistance_ohm = kNaN;  ///< ohm; the pack's
  double internal_resistance_std_ohm = kNaN;  ///< ohm; one standard deviation
  double open_circuit_voltage_v = kNaN;  ///< V; the pack at rest now
  std::string charge_basis;  ///< what the state of charge rests on
  double remaining_ah = kNaN;  ///< charge drawn until the loaded cut-off (or PX4's empty)
  double hover_endurance_s = kNaN;  ///< s; hover time left to the loaded cut-off
  double hover_endurance_std_s = kNaN;  ///< from the state of charge's and the resistance's spread
  /// s; the 90 % interval of the hover time left: what the node does not know yet (the charge and
  /// where the pack's knee lies, the polarisation still to build, a cold pack's lost capacity, the
  /// capacity's spread), calibrated on the battery family (docs/capability.md). NaN with the endurance.
  ///@{
  double hover_endurance_low_s = kNaN;
  double hover_endurance_high_s = kNaN;
  ///@}
  std::string endurance_basis;          ///< how it was computed, or why it is NaN (withheld: ...)
  bool payload_over_limit = false;       ///< max_additional_payload_kg < 0
  bool endurance_below_reserve = false;  ///< hover_endurance_s < reserve_s
};

/// Computes the capability answers (ROS-free; evaluate() at CapabilityConfig::rate_hz,
/// addBattery() per battery message). The endurance integrates the hover discharge
/// (integrateHoverDischarge, as compare_models does) from the estimated state of charge along the
/// open-circuit curve until the loaded voltage reaches the cut-off.
class CapabilityEstimator {
 public:
  /// Throws FieldError for a bad config, or a pwm_max_us at or below the model's lowest PWM.
  /// `model` must outlive the estimator (the Estimator's own).
  CapabilityEstimator(const PropulsionModel& model, int motors, CapabilityConfig config);

  /// One battery message at `time_s`: its voltage in V, what else it reports, and the motors'
  /// modelled total current in A (NaN if none), used when no current is measured. O(1).
  void addBattery(double time_s, double voltage_v, const BatteryReport& battery, double modelled_current_a);

  /// The answers for the estimator's last output and the effects' signals now (the vertical speed
  /// is taken as 0: hover and the thrust at rest at the top of the range).
  CapabilityReport evaluate(const EstimatorOutput& output, const effects::Signals& signals = {}) const;

  /// As validated.
  const CapabilityConfig& config() const { return config_; }
  /// The pack's estimator; nullopt without a battery configured.
  const std::optional<BatteryEstimator>& battery() const { return battery_; }
  /// Whether a flight has been flown and the pack has rested since (PackLearner); false without a
  /// battery configured.
  bool packFlightFinished() const { return learner_ && learner_->flightFinished(); }
  /// s the pack must still rest before its landed flight is learned; NaN when no flight awaits it.
  double packRestLeftS() const;
  /// `previous` with the finished flight learned (PackLearner::learned), and the learner starts
  /// on the next flight. `previous` unchanged when no flight has finished.
  PackRecord learnPack(const PackRecord& previous);
  /// The pack flown is `record`'s (identified by the first battery message's serial number):
  /// the battery estimator starts from what it holds. False, and nothing changed, once a battery
  /// reading has been taken or without a battery configured.
  bool usePack(const PackRecord& record);

 private:
  /// The battery estimator and the pack learner from the configuration (none without a battery).
  void startBattery();
  /// Thrust and current of all motors at the top PWM with the terminals at `voltage_v`.
  OperatingPoint fullThrottle(double voltage_v, const Correction& correction) const;
  void evaluatePayload(const Correction& correction, CapabilityReport* c) const;
  void evaluateEndurance(const Correction& correction, CapabilityReport* c) const;
  /// A model without current: the measured current held until the cut-off.
  void evaluateEnduranceAtMeasuredCurrent(CapabilityReport* c) const;
  HoverDischarge discharge(double state_of_charge, double resistance_ohm, double thrust_per_motor_n,
                           const Correction& correction) const;

  const PropulsionModel& model_;
  int motors_;
  CapabilityConfig config_;
  double pwm_max_us_;
  std::optional<BatteryEstimator> battery_;
  std::optional<PackLearner> learner_;
  bool battery_read_ = false;
  double px4_remaining_ = kNaN;
  double measured_current_a_ = kNaN;
  double temperature_c_ = kNaN;  // the pack's, reported or configured; NaN: unknown
  double unmodelled_current_a_ = kNaN;  // measured less modelled, low-passed while the motors run
  double unmodelled_s_ = kNaN;          // time of its last update
};

/// The Capability diagnostic: WARN when the payload exceeds its limit, the hover endurance is below
/// the reserve or a motor is flagged (each named with its figures), OK otherwise, with the figures
/// and the centre-of-gravity offset as values.
HealthStatus judgeCapability(const CapabilityReport& capability, const MotorHealthVerdict& health,
                             const CapabilityConfig& config);

}  // namespace propulsion_estimator
