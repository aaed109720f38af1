#pragma once

#include <limits>
#include <vector>

namespace propulsion_estimator {

/// An output as a polynomial in the drive the ESC applies to the motor,
/// u = min(max(0, PWM - pwm_zero_us), pwm_full_us - pwm_zero_us) / 1000 us * V (in ms V, about
/// duty x supply voltage): y = sum_k c_k u^k. It carries the propulsion chain's shape: below
/// pwm_zero_us the rotor does not turn, above it thrust, current, power and rotor speed follow duty x
/// voltage, so a curve fitted at a full battery holds at a low one; above pwm_full_us, the ESC's
/// full-throttle end point, the duty is 100 % and only the voltage counts (infinite: the bench never
/// reached it). With every c_k >= 0 it is non-decreasing in PWM and in voltage everywhere, in the
/// bench's domain and beyond it.
class DriveCurve {
 public:
  static constexpr int kMaxDegree = 3;  ///< highest power of u
  static constexpr double kNoFullThrottle = std::numeric_limits<double>::infinity();  ///< pwm_full_us unreached

  /// Throws std::invalid_argument for no coefficient, more than kMaxDegree + 1, a pwm_zero_us or
  /// coefficient that is not finite, or a pwm_full_us that is NaN or not above pwm_zero_us.
  DriveCurve(double pwm_zero_us, std::vector<double> coefficients, double pwm_full_us = kNoFullThrottle);

  /// The drive u in ms V at a PWM (us) and voltage (V).
  double drive(double pwm_us, double voltage_v) const;
  /// The output in its file unit.
  double evaluate(double pwm_us, double voltage_v) const;

  /// x0, us: the PWM at which the rotor starts.
  double pwmZeroUs() const { return pwm_zero_us_; }
  /// us: the PWM above which the duty no longer rises; kNoFullThrottle when the bench never reached it.
  double pwmFullUs() const { return pwm_full_us_; }
  const std::vector<double>& coefficients() const { return coefficients_; }  ///< c_0, c_1, ...
  /// The highest power of u.
  int degree() const { return static_cast<int>(coefficients_.size()) - 1; }

 private:
  double pwm_zero_us_;
  std::vector<double> coefficients_;
  double pwm_full_us_;
};

}  // namespace propulsion_estimator
