#pragma once

#include <utility>
#include <vector>

namespace propulsion_estimator {

/// One term p_ij * x^i * v^j of a response surface.
struct PolynomialTerm {
  int pwm_power = 0;  ///< i, the power of x
  int voltage_power = 0;  ///< j, the power of v
  double coefficient = 0.0;  ///< p_ij
};

/// A polynomial in two variables, x (PWM) and v (voltage), both already centred and scaled by
/// the caller. Evaluation allocates nothing.
class Polynomial2D {
 public:
  static constexpr int kMaxPower = 9;  ///< highest power of either variable

  Polynomial2D() = default;
  /// Throws std::invalid_argument for a power outside [0, kMaxPower] or a repeated (i, j).
  explicit Polynomial2D(std::vector<PolynomialTerm> terms);

  double evaluate(double x, double v) const;  ///< the sum of the terms at (x, v)

  /// As given, in order.
  const std::vector<PolynomialTerm>& terms() const { return terms_; }
  /// The highest power of x in any term.
  int maxPwmPower() const { return max_pwm_power_; }
  /// The highest power of v in any term.
  int maxVoltagePower() const { return max_voltage_power_; }

 private:
  std::vector<PolynomialTerm> terms_;
  int max_pwm_power_ = 0;
  int max_voltage_power_ = 0;
};

/// The (i, j) powers of MATLAB's polyXY model, which the thesis used: i <= x_degree,
/// j <= v_degree and i + j <= max(x_degree, v_degree), ordered by total degree then by i
/// descending (p00, p10, p01, p20, p11, p02, ...).
std::vector<std::pair<int, int>> polynomialBasis(int x_degree, int v_degree);

}  // namespace propulsion_estimator
