// Variants of a loaded model for the tests: the same surfaces under another policy.
#pragma once

#include <array>

#include "propulsion_estimator/model/propulsion_model.h"

// The same surfaces, effects and thrust_from_rpm with `policy` outside the domain.
inline propulsion_estimator::PropulsionModel withOutsidePolicy(const propulsion_estimator::PropulsionModel& model,
                                                               propulsion_estimator::OutsideDomain policy) {
  namespace pe = propulsion_estimator;
  pe::ModelDomain domain = model.domain();
  domain.outside = policy;
  std::array<pe::OutputDefinition, pe::kOutputCount> outputs;
  for (pe::Output output : pe::kAllOutputs) outputs[static_cast<int>(output)] = model.output(output);
  pe::PropulsionModel variant(model.metadata(), domain, outputs, model.effects());
  variant.setRpmThrust(model.rpmThrust());
  return variant;
}
