#include "propulsion_estimator/gap/diagnosis.h"

namespace propulsion_estimator {
namespace gap {

effects::ModelEffects correctedEffects(const Diagnosis& diagnosis) {
  effects::ModelEffects corrected = diagnosis.fitted;
  if (!foldsHealthyLevel(diagnosis)) return corrected;
  const double factor = diagnosis.motors.reference_thrust_factor;
  const double fraction = corrected.parameter(effects::Kind::kThrustLoss).value_or(0.0);
  corrected.setParameter(effects::Kind::kThrustLoss, 1.0 - factor * (1.0 - fraction));
  return corrected;
}

bool foldsHealthyLevel(const Diagnosis& diagnosis) { return diagnosis.motors.reference_thrust_factor != 1.0; }

}  // namespace gap
}  // namespace propulsion_estimator
