#include "propulsion_estimator/sim/flight/flight_sensors.h"

#include <string>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace sim {
namespace {

void requireRate(const char* field, double rate_hz) { requirePositive(field, rate_hz, 500.0, " Hz"); }

void requireSigma(const char* field, double sigma) { requireWithin(field, sigma, 0.0, 1e3); }

}  // namespace

void FlightSensorParams::validate() const {
  requireRate("battery_rate_hz", battery_rate_hz);
  requireRate("imu_rate_hz", imu_rate_hz);
  requireRate("pose_rate_hz", pose_rate_hz);
  requireRate("pressure_rate_hz", pressure_rate_hz);
  requireRate("air_temperature_rate_hz", air_temperature_rate_hz);
  requireRate("rangefinder_rate_hz", rangefinder_rate_hz);
  requireRate("motor_temperature_rate_hz", motor_temperature_rate_hz);
  requireSigma("battery_voltage_sigma_v", battery_voltage_sigma_v);
  requireSigma("battery_current_sigma_a", battery_current_sigma_a);
  requireSigma("gyro_sigma_rad_s", gyro_sigma_rad_s);
  requireSigma("accel_sigma_m_s2", accel_sigma_m_s2);
  requireSigma("orientation_sigma_rad", orientation_sigma_rad);
  requireSigma("position_sigma_m", position_sigma_m);
  requireSigma("velocity_sigma_m_s", velocity_sigma_m_s);
  requirePositive("navigation_error_correlation_s", navigation_error_correlation_s, 1000.0, " s");
  requireSigma("pressure_sigma_pa", pressure_sigma_pa);
  requireSigma("air_temperature_sigma_c", air_temperature_sigma_c);
  requireSigma("rangefinder_sigma_m", rangefinder_sigma_m);
  requireSigma("motor_temperature_sigma_c", motor_temperature_sigma_c);
  requireWithin("esc_telemetry_rate_hz", esc_telemetry_rate_hz, 0.0, 500.0, " Hz");
  requireWithin("esc_pole_pairs", esc_pole_pairs, 1, 30);
  requireSigma("esc_rpm_sigma", esc_rpm_sigma);
  requireSigma("esc_current_sigma_a", esc_current_sigma_a);
  requireWithin("esc_current_gain_sigma", esc_current_gain_sigma, 0.0, 0.2);
  requireSigma("esc_current_offset_sigma_a", esc_current_offset_sigma_a);
  requireSigma("esc_voltage_sigma_v", esc_voltage_sigma_v);
  requireWithin("esc_voltage_gain_sigma", esc_voltage_gain_sigma, 0.0, 0.2);
  requireWithin("esc_dropout_probability", esc_dropout_probability, 0.0, 0.9);
  if (!(rangefinder_min_m >= 0.0 && rangefinder_min_m < rangefinder_max_m)) {
    throw FieldError("rangefinder_min_m", formatNumber(rangefinder_min_m) + " is not below rangefinder_max_m " +
                                              formatNumber(rangefinder_max_m));
  }
}

}  // namespace sim
}  // namespace propulsion_estimator
