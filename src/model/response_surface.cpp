#include "propulsion_estimator/model/response_surface.h"

namespace propulsion_estimator {

bool InputScaling::isIdentity() const {
  return pwm_center_us == 0.0 && pwm_scale_us == 1.0 && voltage_center_v == 0.0 && voltage_scale_v == 1.0;
}

ResponseSurface::ResponseSurface(Polynomial2D numerator, InputScaling scaling)
    : numerator_(std::move(numerator)), scaling_(scaling) {}

ResponseSurface::ResponseSurface(Polynomial2D numerator, Polynomial2D denominator, InputScaling scaling)
    : numerator_(std::move(numerator)), denominator_(std::move(denominator)), scaling_(scaling) {}

ResponseSurface::ResponseSurface(DriveCurve drive_curve) : drive_curve_(std::move(drive_curve)) {}

double ResponseSurface::evaluate(double pwm_us, double voltage_v) const {
  if (drive_curve_) return drive_curve_->evaluate(pwm_us, voltage_v);
  const double x = (pwm_us - scaling_.pwm_center_us) / scaling_.pwm_scale_us;
  const double v = (voltage_v - scaling_.voltage_center_v) / scaling_.voltage_scale_v;
  const double top = numerator_.evaluate(x, v);
  return denominator_ ? top / denominator_->evaluate(x, v) : top;
}

}  // namespace propulsion_estimator
