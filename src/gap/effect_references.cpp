// What the effects are read against: the air and motor warmth of effectBaseline (the bench's, or
// the healthy flights' of a reference), the model's full thrust and the rotors' height.
#include <cmath>

#include "diagnoser.h"
#include "propulsion_estimator/model/effect_baseline.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

effects::ModelEffects Diagnoser::references() const {
  effects::ModelEffects references;
  const EffectBaseline baseline = effectBaseline(model_.metadata(), config_.motor_reference);
  references.air_reference_density_kg_m3 = baseline.air_density_kg_m3;
  references.motor_reference_c = baseline.motor_temperature_c;
  references.full_thrust_n = model_.fullThrustN();
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
