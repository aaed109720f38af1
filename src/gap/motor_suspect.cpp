// The diagnosis' motor balance: which motor is off alone, its thrust factor, and the healthy
// vehicle's level against the model, all carried by the views the effects are sought with.
#include "diagnoser.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

void Diagnoser::balanceMotors() {
  std::vector<int> channels = config_.channels;
  if (channels.empty()) {
    for (int k = 0; k < motorCount(); ++k) channels.push_back(k + 1);
  }
  diagnosis_.motors = gap::balanceMotors(views_, vehicle_, blocks_, channels, config_);
  // Against a reference of healthy flights, effects are changes from that vehicle.
  if (const std::optional<MotorReference>& reference = config_.motor_reference) {
    views_.setLevels(reference->thrust_factor, reference->current_thrust_factor, reference->rpm_thrust_factor);
    if (!std::isnan(reference->thrust_factor)) diagnosis_.motors.reference_thrust_factor = reference->thrust_factor;
  }
  if (!diagnosis_.motors.suspect_channel) return;
  for (std::size_t k = 0; k < diagnosis_.motors.motors.size(); ++k) {
    const MotorGap& motor = diagnosis_.motors.motors[k];
    if (motor.channel == *diagnosis_.motors.suspect_channel) {
      // The payloads' moments give the gap as the share of thrust the motor lacks, refined against
      // the weighed thrust; the shares give it as the model's excess over the motor's thrust,
      // whatever the weighed mass (a mass off by a few per cent would pull a fitted factor along).
      const double gap = motor.thrust_gap_pct / 100.0;
      diagnosis_.motors.suspect_thrust_factor = diagnosis_.motors.basis == MotorBasis::kPayloads
                                                    ? suspectThrustFactor(static_cast<int>(k), gap)
                                                    : 1.0 / (1.0 + gap);
      views_.setMotorScale(static_cast<int>(k), diagnosis_.motors.suspect_thrust_factor);
    }
  }
}

// The yaw balance gives the suspect's gap assuming its propeller turns thrust into drag torque
// as the bench propeller did; a damaged or smaller one does not quite. Its thrust factor is fitted
// to the weighed thrust instead (least squares on the PWM view), within [1 - 2 gap, 1]: weaker
// than modelled, by at most twice what the balance says.
double Diagnoser::suspectThrustFactor(int motor, double yaw_gap) const {
  const effects::ModelEffects plain = references();
  double sum_xy = 0.0, sum_xx = 0.0;
  for (const Block& block : blocks_) {
    // No effect is selected yet: the PWM view is the surfaces' thrust along each rotor's axis.
    const double mine = views_.motorThrust(block.pwm_us[motor], block.voltage_v) * block.axis_up[motor];
    const double others = views_.pwmView(block, plain) - mine;
    const double weight = 1.0 / (block.truth_n * block.truth_n);
    sum_xy += weight * (block.truth_n - others) * mine;
    sum_xx += weight * mine * mine;
  }
  const double fitted = sum_xx > 0.0 ? sum_xy / sum_xx : 1.0 - yaw_gap;
  return std::clamp(fitted, 1.0 - 2.0 * std::abs(yaw_gap), 1.0);
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
