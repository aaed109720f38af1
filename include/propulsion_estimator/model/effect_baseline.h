#pragma once

#include <optional>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/model/motor_reference.h"
#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {

/// What the effects' laws read a flight's air and motor warmth against.
struct EffectBaseline {
  double air_density_kg_m3 = kNaN;  ///< kg/m^3; NaN where unknown
  double motor_temperature_c = kNaN;  ///< deg C; NaN where unknown
};

/// The healthy flights' air and motor temperature where `reference` holds them (the thrust level a
/// reference folds into a model was flown in them, so effects are changes from them), else the
/// bench's from `metadata` (its air temperature standing for the motors'); NaN where neither
/// gives one. The one rule for the diagnosis and the corrected model alike: a model derives its
/// air_density reference from it (PropulsionModel::setMotorReference, withEffects); the motor
/// temperature reaches a corrected model as motor_temperature's reference_c, which the diagnosis
/// writes from it. Throws nothing.
EffectBaseline effectBaseline(const ModelMetadata& metadata, const std::optional<MotorReference>& reference);

}  // namespace propulsion_estimator
