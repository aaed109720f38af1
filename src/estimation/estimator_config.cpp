#include "propulsion_estimator/estimation/estimator_config.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "propulsion_estimator/common/config_error.h"

namespace propulsion_estimator {
namespace {

constexpr double kMaxRateHz = 1000.0;

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
  requirePositive(static_pressure_timeout_s, "static_pressure/timeout_s");
  requirePositive(air_temperature_timeout_s, "air_temperature/timeout_s");
  requirePositive(rangefinder_timeout_s, "rangefinder/timeout_s");
  requirePositive(motor_temperature_timeout_s, "motor_temperature/timeout_s");
  requirePositive(accel_filter_s, "imu/accel_filter_s");
  requirePositive(accel_bias_filter_s, "imu/accel_bias_filter_s");
  requirePositive(max_rate_hz, "max_rate_hz");
  if (max_rate_hz > kMaxRateHz) {
    message << "max_rate_hz: " << max_rate_hz << " is above " << kMaxRateHz << " (RCOut comes at 10-50 Hz)";
    throw ConfigError(message.str());
  }
  requirePositive(clock_jump_reset_s, "clock_jump_reset_s");
  if (empty_mass_kg) requirePositive(*empty_mass_kg, "empty_mass_kg");
  hover.validate();
  payload.validate();
  const double window_samples = payload.averaging_window_s * max_rate_hz;
  if (static_cast<double>(payload.min_samples) > window_samples) {
    message << "payload/min_samples: " << payload.min_samples << " samples never fit in payload/averaging_window_s "
            << payload.averaging_window_s << " s at max_rate_hz " << max_rate_hz;
    throw ConfigError(message.str());
  }
}

}  // namespace propulsion_estimator
