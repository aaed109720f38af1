#pragma once

#include "propulsion_estimator/core/propulsion_model.h"

namespace propulsion_estimator {

// Grid on which a model is checked: pwm_points x voltage_points, both ends included.
struct ValidationGrid {
  int pwm_points = 36;
  int voltage_points = 15;
};

// Refuses (ConfigError naming the output and a grid point) a model whose outputs are not finite
// anywhere on the grid, whose rational surfaces have a pole in the domain, whose thrust, current,
// power or rpm is negative at the top of the PWM range, or whose efficiency is negative anywhere.
void validateModelOnGrid(const PropulsionModel& model, const ValidationGrid& grid = {});

}  // namespace propulsion_estimator
