#pragma once

#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {

/// Refuses (FieldError "outputs.<output>" naming a grid point) a model whose outputs are not finite
/// anywhere on a 36 x 15 grid over its domain (ends included; with `outside: clamp` or `reject` only
/// the grid points the bench covered), whose rational surfaces have a pole
/// in the domain, whose thrust, current, power or rpm is negative at the top of the PWM range, or
/// whose efficiency is negative anywhere.
void validateModelOnGrid(const PropulsionModel& model);

}  // namespace propulsion_estimator
