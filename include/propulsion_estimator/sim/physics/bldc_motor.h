#pragma once

#include <string>

namespace propulsion_estimator {
namespace sim {

/// Resistance temperature coefficient of annealed copper at 20 deg C (IEC 60028: 0.00393 /K).
constexpr double kCopperTemperatureCoefficientPerC = 0.00393;
constexpr double kCopperReferenceTemperatureC = 20.0;  ///< deg C at which that coefficient holds

/// Brushless DC motor as its brushed-DC equivalent (M. Drela, "First-Order DC Electric Motor
/// Model", MIT 2007): back-EMF and torque constant 1/kv, a winding resistance, and a no-load
/// current standing for iron and bearing losses. Magnet flux (hence 1/kv) and winding resistance
/// depend on the winding temperature, which a lumped thermal model tracks.
struct BldcMotorParams {
  std::string name;  ///< for metadata and messages
  double kv_rpm_per_v = 0.0;  ///< rpm per V, at reference_temperature_c
  double winding_resistance_ohm = 0.0;  ///< at reference_temperature_c
  double no_load_current_a = 0.0;  ///< A, at reference_temperature_c
  double reference_temperature_c = 0.0;             ///< winding temperature at which kv and resistance hold
  double flux_temperature_coefficient_per_c = 0.0;  ///< magnet remanence; NdFeB about -0.0012
  double rotor_inertia_kg_m2 = 0.0;                 ///< bell and magnets, without the propeller
  double thermal_capacity_j_per_c = 0.0;  ///< J per deg C, winding and stator
  double thermal_resistance_c_per_w = 0.0;  ///< winding to air, with propeller wash

  /// Throws FieldError (motor.*) for a value outside its physical range.
  void validate() const;
};

/// Electrical constants at one winding temperature.
struct MotorConstants {
  double torque_constant_nm_per_a = 0.0;  ///< = back-EMF constant in V s/rad
  double resistance_ohm = 0.0;            ///< winding only
  double no_load_current_a = 0.0;  ///< A
};

/// Winding resistance follows copper, R(T) = R(20 C) (1 + 0.00393 (T - 20)), scaled so that it is
/// the given resistance at the reference temperature; the torque constant follows the magnet
/// flux, k(T) = k_ref (1 + flux_coefficient (T - T_ref)).
MotorConstants motorConstantsAt(const BldcMotorParams& motor, double winding_temperature_c);

/// Winding temperature after `dt_s` with `heat_w` dissipated and the motor cooled towards
/// `air_c` through `thermal_resistance_c_per_w` (exact for heat and air constant over the step).
double nextWindingTemperature(const BldcMotorParams& motor, double temperature_c, double heat_w, double air_c,
                              double thermal_resistance_c_per_w, double dt_s);

}  // namespace sim
}  // namespace propulsion_estimator
