#include "propulsion_estimator/model/drive_curve.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace propulsion_estimator {

DriveCurve::DriveCurve(double pwm_zero_us, std::vector<double> coefficients, double pwm_full_us)
    : pwm_zero_us_(pwm_zero_us), coefficients_(std::move(coefficients)), pwm_full_us_(pwm_full_us) {
  if (coefficients_.empty() || coefficients_.size() > kMaxDegree + 1) {
    throw std::invalid_argument("a drive curve has 1 to " + std::to_string(kMaxDegree + 1) + " coefficients c0.., not " +
                                std::to_string(coefficients_.size()));
  }
  if (!std::isfinite(pwm_zero_us_)) throw std::invalid_argument("pwm_zero_us is not finite");
  if (!(pwm_full_us_ > pwm_zero_us_)) {
    throw std::invalid_argument("pwm_full_us " + std::to_string(pwm_full_us_) + " is not above pwm_zero_us " +
                                std::to_string(pwm_zero_us_));
  }
  for (double c : coefficients_) {
    if (!std::isfinite(c)) throw std::invalid_argument("a coefficient is not finite");
  }
}

double DriveCurve::drive(double pwm_us, double voltage_v) const {
  return std::clamp(pwm_us - pwm_zero_us_, 0.0, pwm_full_us_ - pwm_zero_us_) * 1e-3 * voltage_v;
}

double DriveCurve::evaluate(double pwm_us, double voltage_v) const {
  const double u = drive(pwm_us, voltage_v);
  double sum = 0.0;
  for (auto c = coefficients_.rbegin(); c != coefficients_.rend(); ++c) sum = sum * u + *c;
  return sum;
}

}  // namespace propulsion_estimator
