#include "propulsion_estimator/estimation/estimator_config.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
void EstimatorConfig::validate(std::size_t rotors) const {
  if (motor_channels.empty()) throw FieldError("motor_channels", "must list at least one channel");
  for (int channel : motor_channels) {
    if (channel < 1 || channel > 32) {
      throw FieldError("motor_channels",
                       "channel " + std::to_string(channel) + " is outside 1..32 (channels are 1-based)");
    }
    if (std::count(motor_channels.begin(), motor_channels.end(), channel) > 1) {
      throw FieldError("motor_channels", "channel " + std::to_string(channel) + " is listed twice");
    }
  }
  if (motor_channels.size() != rotors) {
    throw FieldError("motor_channels", std::to_string(motor_channels.size()) + " channels for a vehicle with " +
                                           std::to_string(rotors) + " rotors");
  }
  if (!(disarmed_pwm_max_us >= 0.0) || !std::isfinite(disarmed_pwm_max_us)) {
    throw FieldError("disarmed_pwm_max_us", "must be a non-negative number, got " + formatNumber(disarmed_pwm_max_us));
  }
  requirePositive("battery_timeout_s", battery_timeout_s);
  requirePositive("imu/timeout_s", imu_timeout_s);
  requirePositive("velocity/timeout_s", velocity_timeout_s);
  for (input::Scalar scalar : input::kAllScalars) requirePositive(input::timeoutParameter(scalar), inputTimeoutS(scalar));
  requirePositive("imu/accel_filter_s", accel_filter_s);
  requirePositive("imu/accel_bias_filter_s", accel_bias_filter_s);
  requirePositive("clock_jump_reset_s", clock_jump_reset_s);
  requirePositive("max_stamp_ahead_s", max_stamp_ahead_s);
  if (empty_mass_kg) requirePositive("empty_mass_kg", *empty_mass_kg);
  hover.validate();
  payload.validate();
}

}  // namespace propulsion_estimator
