#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/estimation/motor_health.h"
#include "propulsion_estimator/onboard/capability.h"
#include "propulsion_estimator/onboard/health_summary.h"
#include "propulsion_estimator/onboard/model_check.h"
#include "propulsion_estimator/onboard/rpm_mass_view.h"

namespace propulsion_estimator {

/// What the onboard session computes from: the estimator's, the capability's and the live model
/// check's configuration, and where ~capability's hover mass comes from.
struct OnboardConfig {
  EstimatorConfig estimator;       ///< the estimator's parameters
  CapabilityConfig capability;     ///< capability/... (the motor-health check's among them)
  ModelCheckConfig esc_telemetry;  ///< esc_telemetry/... (the live model check)
  /// "pwm": the surfaces at PWM and voltage; "rpm": the measured rotor speeds through the model's
  /// thrust_from_rpm while every motor's telemetry is fresh (the PWM view otherwise).
  std::string mass_view = "pwm";
};

/// Everything ~capability publishes at one moment, and what it was judged from.
struct CapabilityState {
  CapabilityReport capability;      ///< payload limits and endurance
  MotorHealthVerdict motor_health;  ///< the onboard motor-health check
  ModelCheckReport model_check;     ///< the live ESC check
  bool rpm_mass_view = false;       ///< the hover mass came from the rpm view
  double rpm_view_mass_kg = kNaN;   ///< kg; NaN without thrust_from_rpm or before a hover sample
  double supply_applied_ohm = kNaN; ///< ohm, the supply resistance applied as the effect; NaN: none
};

/// The vehicle's whole onboard computation, ROS-free, fed one reading at a time: the estimator,
/// the motor-health check, the live model check of ESC telemetry, the rpm mass view and the
/// capability, with the loop from the model check's supply resistance back into the estimator.
/// estimator_node adapts topics to it; every offline replay (the estimate on a log, diagnose_gap's
/// replays) drives it alike, so a replay says what the node would have said. Times are receipt
/// times, s, on one clock; each reader that judges a verdict first expires a hover whose inputs
/// stopped. Not thread-safe (the node holds it under its mutex).
class OnboardSession {
 public:
  /// Throws ConfigError for a mass_view "rpm" on a model without thrust_from_rpm (naming
  /// `model_name`) and FieldError for a configuration that does not fit the vehicle.
  OnboardSession(PropulsionModel model, Vehicle vehicle, const OnboardConfig& config,
                 const std::string& model_name = "the model");

  /// Whether the model's effects read `signal` (the node subscribes to those topics only; the
  /// session drops a reading of a signal nothing reads, as the node never receives it).
  bool reads(effects::Signal signal) const;
  /// Whether the session takes readings of `scalar`: the static pressure always (the hover check's
  /// vertical speed without velocity), another only when an effect reads a signal prepared from it.
  bool readsInput(input::Scalar scalar) const { return inputs_read_[input::index(scalar)]; }

  /// One RCOut message (µs per channel) stamped `stamp_s`: estimated, and when accepted, taken
  /// by the motor-health check, the model check and the rpm view. Returns the estimator's verdict.
  Rejection addMotorOutputs(double stamp_s, double now_s, const std::uint16_t* channels, std::size_t count);
  /// The battery: voltage (V), current (A, NaN when not measured), percentage (0-1, NaN when not
  /// reported), the pack's temperature (deg C, NaN when not reported). Returns the first refusal of the voltage or the current, kNone when both were taken.
  Rejection addBattery(double now_s, double voltage_v, double current_a, double percentage,
                       double temperature_c = kNaN);
  /// The attitude and the specific force, m/s², body axes.
  Rejection addImu(double now_s, const Eigen::Quaterniond& orientation, const Eigen::Vector3d& specific_force);
  Rejection addVerticalSpeed(double now_s, double vertical_speed_m_s);  ///< m/s, up positive
  Rejection addHorizontalVelocity(double now_s, double east_m_s, double north_m_s);  ///< m/s
  /// A reading of `scalar` in its ScalarSpec's unit (Estimator::addInput); dropped unless read.
  Rejection addInput(input::Scalar scalar, double now_s, double value);
  /// A sensor_msgs/Range: m and the sensor's limits (Estimator::addRange); dropped unless read.
  Rejection addRange(double now_s, double range_m, double min_range_m, double max_range_m);
  /// One decoded ESC telemetry message (the live model check).
  void addEscTelemetry(double now_s, const EscTelemetry& message);

  /// ~capability's contents at `now_s`.
  CapabilityState capability(double now_s);
  /// The "Payload" diagnostic at `now_s`.
  HealthStatus payloadHealth(double now_s);
  /// ~detect_hover's answer at `now_s`: whether hovering, and the verdict with the averaged mass.
  std::pair<bool, std::string> detectHover(double now_s);
  /// ~tare at `now_s`.
  TareResult tare(double now_s) { return estimator_.tare(now_s); }
  /// ~reset: the estimator's windows and tare, the checks' averages and the rpm view.
  void reset();
  /// An empty mass known before the flight (the tare file).
  void setEmptyMass(double mass_kg, EmptyMassSource source) { estimator_.setEmptyMass(mass_kg, source); }

  /// Whether ~capability's mass comes from the rpm view at `now_s`.
  bool rpmViewInUse(double now_s) const;
  /// The rpm view, when the model has thrust_from_rpm.
  const std::optional<RpmMassView>& rpmView() const { return rpm_view_; }
  /// ohm, the supply resistance applied as the model's effect; NaN while none.
  double supplyAppliedOhm() const { return supply_applied_ohm_; }
  /// The live model check: its report at a time, each motor's measurement, the supply resistance.
  const ModelCheck& modelCheck() const { return model_check_; }
  /// The newest motor-health verdict (nothing to expire: its window is the accepted messages').
  MotorHealthVerdict motorHealth() const { return motor_health_.verdict(); }

  const Estimator& estimator() const { return estimator_; }  ///< its output, counters and model
  const CapabilityEstimator& capabilityEstimator() const { return capability_; }  ///< its config and battery
  /// Whether a flight has been flown and the pack has rested since (the pack file is due).
  bool packFlightFinished() const { return capability_.packFlightFinished(); }
  /// `previous` with the finished flight learned; the next flight is learned afresh
  /// (CapabilityEstimator::learnPack).
  PackRecord learnPack(const PackRecord& previous) { return capability_.learnPack(previous); }
  /// The pack flown is `record`'s, before any battery reading (CapabilityEstimator::usePack).
  bool usePack(const PackRecord& record) { return capability_.usePack(record); }
  const OnboardConfig& config() const { return config_; }  ///< as given

 private:
  void applySupplyResistance();

  OnboardConfig config_;
  Estimator estimator_;
  CapabilityEstimator capability_;
  MotorHealth motor_health_;
  ModelCheck model_check_;
  std::optional<RpmMassView> rpm_view_;
  bool battery_current_ = false;  ///< a supply_resistance effect (or its application) reads it
  input::PerScalar<bool> inputs_read_{};  ///< see readsInput
  double supply_applied_ohm_ = kNaN;
  EstimatorOutput rpm_output_;  ///< the estimator's output with the rpm view's mass
};

}  // namespace propulsion_estimator
