#include "propulsion_estimator/core/estimator_config.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "propulsion_estimator/core/config_error.h"

namespace propulsion_estimator {
namespace {

void requirePositive(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    std::ostringstream message;
    message << name << ": must be a positive number, got " << value;
    throw ConfigError(message.str());
  }
}

}  // namespace

void EstimatorConfig::validate(std::size_t rotors) const {
  std::ostringstream message;
  if (motor_channels.empty()) throw ConfigError("motor_channels: must list at least one channel");
  for (int channel : motor_channels) {
    if (channel < 1 || channel > 32) {
      message << "motor_channels: channel " << channel << " is outside 1..32 (channels are 1-based)";
      throw ConfigError(message.str());
    }
    if (std::count(motor_channels.begin(), motor_channels.end(), channel) > 1) {
      message << "motor_channels: channel " << channel << " is listed twice";
      throw ConfigError(message.str());
    }
  }
  if (motor_channels.size() != rotors) {
    message << "motor_channels: " << motor_channels.size() << " channels for a vehicle with " << rotors << " rotors";
    throw ConfigError(message.str());
  }
  if (!(disarmed_pwm_max_us >= 0.0) || !std::isfinite(disarmed_pwm_max_us)) {
    message << "disarmed_pwm_max_us: must be a non-negative number, got " << disarmed_pwm_max_us;
    throw ConfigError(message.str());
  }
  requirePositive(battery_timeout_s, "battery_timeout_s");
  requirePositive(imu_timeout_s, "imu/timeout_s");
  requirePositive(velocity_timeout_s, "velocity/timeout_s");
  requirePositive(accel_filter_s, "imu/accel_filter_s");
  requirePositive(accel_bias_filter_s, "imu/accel_bias_filter_s");
  requirePositive(max_rate_hz, "max_rate_hz");
  requirePositive(clock_jump_reset_s, "clock_jump_reset_s");
  if (empty_mass_kg) requirePositive(*empty_mass_kg, "empty_mass_kg");
  hover.validate();
  payload.validate();
}

}  // namespace propulsion_estimator
