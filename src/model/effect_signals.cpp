#include "propulsion_estimator/model/effect_signals.h"

#include <cmath>

#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace effects {

double airDensityKgM3(double static_pressure_pa, double air_temperature_c) {
  return static_pressure_pa / (kSpecificGasConstantDryAir * (air_temperature_c + kZeroCelsiusInKelvin));
}

double dischargeCurrentA(double reported_a) { return std::fabs(reported_a); }

double heightAboveGroundM(double range_m, double body_z_up) {
  if (!(body_z_up > 0.0)) return kNaN;
  return range_m * body_z_up;
}

Signals prepareSignals(const RawSignals& raw) {
  Signals signals;
  signals.battery_current_a = dischargeCurrentA(raw.battery_current_a);
  signals.air_density_kg_m3 = airDensityKgM3(raw.static_pressure_pa, raw.air_temperature_c);
  signals.height_m = heightAboveGroundM(raw.range_m, raw.body_z_up);
  signals.motor_temperature_c = raw.motor_temperature_c;
  signals.vertical_speed_m_s = raw.vertical_speed_m_s;
  signals.horizontal_speed_m_s = std::hypot(raw.velocity_east_m_s, raw.velocity_north_m_s);
  const bool horizontal = std::isfinite(signals.horizontal_speed_m_s);
  signals.axial_speed_m_s =
      raw.vertical_speed_m_s * raw.body_z_up +
      (horizontal ? raw.velocity_east_m_s * raw.body_z_east + raw.velocity_north_m_s * raw.body_z_north : 0.0);
  return signals;
}

}  // namespace effects
}  // namespace propulsion_estimator
