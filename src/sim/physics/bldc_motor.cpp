#include "propulsion_estimator/sim/physics/bldc_motor.h"

#include <cmath>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace sim {

void BldcMotorParams::validate() const {
  requireWithin("motor.kv_rpm_per_v", kv_rpm_per_v, 10.0, 10000.0, " rpm/V");
  requireWithin("motor.winding_resistance_ohm", winding_resistance_ohm, 0.001, 10.0, " ohm");
  requireWithin("motor.no_load_current_a", no_load_current_a, 0.0, 20.0, " A");
  requireWithin("motor.reference_temperature_c", reference_temperature_c, -40.0, 120.0, " deg C");
  requireWithin("motor.flux_temperature_coefficient_per_c", flux_temperature_coefficient_per_c, -0.005, 0.0, " /deg C");
  // Every rotor has inertia; the speed lag divides by it.
  requirePositive("motor.rotor_inertia_kg_m2", rotor_inertia_kg_m2, 0.01, " kg m^2");
  requireWithin("motor.thermal_capacity_j_per_c", thermal_capacity_j_per_c, 1.0, 10000.0, " J/deg C");
  requireWithin("motor.thermal_resistance_c_per_w", thermal_resistance_c_per_w, 0.01, 100.0, " deg C/W");
}

MotorConstants motorConstantsAt(const BldcMotorParams& motor, double winding_temperature_c) {
  MotorConstants constants;
  const double kt_reference = 1.0 / (motor.kv_rpm_per_v * kRadPerSecPerRpm);
  constants.torque_constant_nm_per_a =
      kt_reference *
      (1.0 + motor.flux_temperature_coefficient_per_c * (winding_temperature_c - motor.reference_temperature_c));
  const auto copperFactor = [](double t) {
    return 1.0 + kCopperTemperatureCoefficientPerC * (t - kCopperReferenceTemperatureC);
  };
  constants.resistance_ohm =
      motor.winding_resistance_ohm * copperFactor(winding_temperature_c) / copperFactor(motor.reference_temperature_c);
  constants.no_load_current_a = motor.no_load_current_a;
  return constants;
}

double nextWindingTemperature(const BldcMotorParams& motor, double temperature_c, double heat_w, double air_c,
                              double thermal_resistance_c_per_w, double dt_s) {
  const double settled = air_c + heat_w * thermal_resistance_c_per_w;
  const double time_constant = motor.thermal_capacity_j_per_c * thermal_resistance_c_per_w;
  return settled + (temperature_c - settled) * std::exp(-dt_s / time_constant);
}

}  // namespace sim
}  // namespace propulsion_estimator
