// What the effects are read against: the bench the model was measured on, or, with a reference of
// the vehicle's healthy flights, the air and motor warmth those flights flew in.
#include <cmath>

#include "diagnoser.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

effects::ModelEffects Diagnoser::references() const {
  effects::ModelEffects references;
  references.bench_air_density_kg_m3 = model_.metadata().benchAirDensity();
  references.full_thrust_n = model_.fullThrustN();
  references.motor_reference_c = model_.metadata().bench_air_temperature_c.value_or(kNaN);
  // A reference's thrust levels hold its flights' air and warmth: effects are changes from those.
  if (const std::optional<MotorReference>& reference = config_.motor_reference) {
    if (std::isfinite(reference->air_density_kg_m3)) references.bench_air_density_kg_m3 = reference->air_density_kg_m3;
    if (std::isfinite(reference->motor_temperature_c)) references.motor_reference_c = reference->motor_temperature_c;
  }
  if (vehicle_.hasGeometry()) {
    double height = 0.0;
    for (const Rotor& rotor : vehicle_.rotors) height += rotor.position_m.z() / vehicle_.rotors.size();
    references.rotor_height_m = height;
  }
  return references;
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
