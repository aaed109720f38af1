#include "propulsion_estimator/fitting/fit_options.h"

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/fitting/grouped_least_squares.h"

namespace propulsion_estimator {
namespace fitting {

void FitOptions::validate() const {
  if (max_pwm_degree < 1 || max_pwm_degree > GroupedLeastSquares::kMaxPwmDegree) {
    throw ConfigError("max PWM degree " + std::to_string(max_pwm_degree) + " is outside 1..5");
  }
  if (max_voltage_degree < 0 || max_voltage_degree > GroupedLeastSquares::kMaxVoltageDegree) {
    throw ConfigError("max voltage degree " + std::to_string(max_voltage_degree) + " is outside 0..3");
  }
  if (!(parsimony >= 0.0)) throw ConfigError("parsimony must not be negative");
  if (min_points < 3) throw ConfigError("min points must be at least 3");
  if (without.count(Output::kThrust)) throw ConfigError("thrust cannot be left out: it is what the estimator is for");
  if (without.count(Output::kEfficiency)) {
    throw ConfigError("efficiency cannot be left out: it is derived from thrust and power at no cost");
  }
  levels.validate();
}

}  // namespace fitting
}  // namespace propulsion_estimator
