#pragma once

#include <optional>

#include "propulsion_estimator/model/polynomial_2d.h"

namespace propulsion_estimator {

/// Centring and scaling of the inputs, x' = (x - center) / scale, which keeps high-degree
/// polynomials in microseconds numerically sane.
struct InputScaling {
  double pwm_center_us = 0.0;  ///< us
  double pwm_scale_us = 1.0;  ///< us
  double voltage_center_v = 0.0;  ///< V
  double voltage_scale_v = 1.0;  ///< V

  bool isIdentity() const;  ///< whether the scaling changes nothing (center 0, scale 1)
};

/// One output of a propulsion model as a function of PWM (us) and voltage (V): a polynomial or a
/// ratio of two polynomials in the scaled inputs. Values are in the unit the model file states.
class ResponseSurface {
 public:
  /// A polynomial surface in the inputs scaled by `scaling` (non-zero scales, checked by the model reader).
  ResponseSurface(Polynomial2D numerator, InputScaling scaling);
  /// A rational surface, numerator / denominator, in the scaled inputs.
  ResponseSurface(Polynomial2D numerator, Polynomial2D denominator, InputScaling scaling);

  /// The value at (pwm_us, voltage_v), in the file's unit; infinite or NaN at a rational surface's pole.
  double evaluate(double pwm_us, double voltage_v) const;

  /// In the scaled inputs.
  const Polynomial2D& numerator() const { return numerator_; }
  /// Absent for a polynomial surface.
  const std::optional<Polynomial2D>& denominator() const { return denominator_; }
  /// How the inputs are centred and scaled.
  const InputScaling& scaling() const { return scaling_; }

 private:
  Polynomial2D numerator_;
  std::optional<Polynomial2D> denominator_;
  InputScaling scaling_;
};

}  // namespace propulsion_estimator
