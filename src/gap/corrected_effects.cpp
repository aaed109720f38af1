#include "propulsion_estimator/gap/diagnosis.h"

namespace propulsion_estimator {
namespace gap {

effects::ModelEffects correctedEffects(const Diagnosis& diagnosis) {
  effects::ModelEffects corrected = diagnosis.fitted;
  const double factor = diagnosis.motors.reference_thrust_factor;
  if (factor == 1.0) return corrected;
  const double fraction = corrected.parameter(effects::Kind::kThrustLoss).value_or(0.0);
  corrected.setParameter(effects::Kind::kThrustLoss, 1.0 - factor * (1.0 - fraction));
  return corrected;
}

}  // namespace gap
}  // namespace propulsion_estimator
