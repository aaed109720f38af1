#include "propulsion_estimator/model/polynomial_2d.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace propulsion_estimator {

Polynomial2D::Polynomial2D(std::vector<PolynomialTerm> terms) : terms_(std::move(terms)) {
  std::array<std::array<bool, kMaxPower + 1>, kMaxPower + 1> seen{};
  for (const PolynomialTerm& term : terms_) {
    if (term.pwm_power < 0 || term.pwm_power > kMaxPower || term.voltage_power < 0 ||
        term.voltage_power > kMaxPower) {
      throw std::invalid_argument("term p" + std::to_string(term.pwm_power) + std::to_string(term.voltage_power) +
                                  " has a power outside 0.." + std::to_string(kMaxPower));
    }
    if (seen[term.pwm_power][term.voltage_power]) {
      throw std::invalid_argument("term p" + std::to_string(term.pwm_power) + std::to_string(term.voltage_power) +
                                  " appears twice");
    }
    seen[term.pwm_power][term.voltage_power] = true;
    max_pwm_power_ = std::max(max_pwm_power_, term.pwm_power);
    max_voltage_power_ = std::max(max_voltage_power_, term.voltage_power);
  }
}

double Polynomial2D::evaluate(double x, double v) const {
  std::array<double, kMaxPower + 1> x_pow;
  std::array<double, kMaxPower + 1> v_pow;
  x_pow[0] = 1.0;
  v_pow[0] = 1.0;
  for (int i = 1; i <= max_pwm_power_; ++i) x_pow[i] = x_pow[i - 1] * x;
  for (int j = 1; j <= max_voltage_power_; ++j) v_pow[j] = v_pow[j - 1] * v;
  double sum = 0.0;
  for (const PolynomialTerm& term : terms_) sum += term.coefficient * x_pow[term.pwm_power] * v_pow[term.voltage_power];
  return sum;
}

std::vector<std::pair<int, int>> polynomialBasis(int x_degree, int v_degree) {
  const int total = std::max(x_degree, v_degree);
  std::vector<std::pair<int, int>> basis;
  for (int degree = 0; degree <= total; ++degree) {
    for (int i = degree; i >= 0; --i) {
      const int j = degree - i;
      if (i <= x_degree && j <= v_degree) basis.emplace_back(i, j);
    }
  }
  return basis;
}

}  // namespace propulsion_estimator
