#include "propulsion_estimator/estimation/estimator_config.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace {

constexpr double kMaxRateHz = 1000.0;
// Samples one window may hold (allocated once): 100 s at 1000 Hz, some MB on a Raspberry Pi.
constexpr double kMaxWindowSamples = 100000.0;

// A window of `span_s` at `rate_hz` within the memory bound.
void requireWindowFits(const std::string& field, double span_s, double rate_hz) {
  if (span_s * rate_hz > kMaxWindowSamples) {
    throw FieldError(field, formatNumber(span_s) + " s at max_rate_hz " + formatNumber(rate_hz) + " needs " +
                                formatNumber(std::ceil(span_s * rate_hz)) + " samples, more than the " +
                                formatNumber(kMaxWindowSamples) + " a window may hold");
  }
}

}  // namespace

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
  requirePositive("static_pressure/timeout_s", static_pressure_timeout_s);
  requirePositive("air_temperature/timeout_s", air_temperature_timeout_s);
  requirePositive("rangefinder/timeout_s", rangefinder_timeout_s);
  requirePositive("motor_temperature/timeout_s", motor_temperature_timeout_s);
  requirePositive("imu/accel_filter_s", accel_filter_s);
  requirePositive("imu/accel_bias_filter_s", accel_bias_filter_s);
  requirePositive("max_rate_hz", max_rate_hz);
  if (max_rate_hz > kMaxRateHz) {
    throw FieldError("max_rate_hz", formatNumber(max_rate_hz) + " is above " + formatNumber(kMaxRateHz) +
                                        " (RCOut comes at 10-50 Hz)");
  }
  requirePositive("clock_jump_reset_s", clock_jump_reset_s);
  requirePositive("max_stamp_ahead_s", max_stamp_ahead_s);
  if (empty_mass_kg) requirePositive("empty_mass_kg", *empty_mass_kg);
  hover.validate();
  payload.validate();
  requireWindowFits("hover/window_s", hover.window_s, max_rate_hz);
  requireWindowFits("payload/averaging_window_s", payload.averaging_window_s, max_rate_hz);
  // Samples come at most max_rate_hz apart: the window's samples span at most one period less than it.
  const double period_s = 1.0 / max_rate_hz;
  if (hover.min_window_fill * hover.window_s > hover.window_s - period_s) {
    throw FieldError("hover/min_window_fill",
                     formatNumber(hover.min_window_fill) + " is never met: at max_rate_hz " +
                         formatNumber(max_rate_hz) + " samples come " + formatPrintf("%.6g", period_s) +
                         " s apart and span at most " +
                         formatPrintf("%.6g", std::max(hover.window_s - period_s, 0.0)) + " s of hover/window_s " +
                         formatNumber(hover.window_s) + " s");
  }
  // Hover samples further apart than the gap each start a new episode: none is ever averaged.
  if (payload.episode_gap_s < period_s) {
    throw FieldError("payload/episode_gap_s", formatNumber(payload.episode_gap_s) +
                                                  " s is shorter than the sample period at max_rate_hz " +
                                                  formatNumber(max_rate_hz) + " (" + formatPrintf("%.6g", period_s) +
                                                  " s): every hover sample would start a new episode");
  }
  const double window_samples = payload.averaging_window_s * max_rate_hz;
  if (static_cast<double>(payload.min_samples) > window_samples) {
    throw FieldError("payload/min_samples",
                     std::to_string(payload.min_samples) + " samples never fit in payload/averaging_window_s " +
                         formatNumber(payload.averaging_window_s) + " s at max_rate_hz " + formatNumber(max_rate_hz));
  }
}

}  // namespace propulsion_estimator
