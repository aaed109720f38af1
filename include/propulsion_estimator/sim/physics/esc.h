#pragma once

#include <string>

namespace propulsion_estimator {
namespace sim {

/// Electronic speed controller as an ideal averaging buck stage: the motor sees duty * input
/// voltage and the ESC draws duty * motor current. The duty follows the pulse width linearly
/// between the ESC's calibrated end points and is clamped to 0..1; at duty 0 the bridge is off.
struct EscParams {
  std::string name;  ///< for metadata and messages
  double pwm_zero_us = 0.0;     ///< pulse width of duty 0 (calibrated low end point)
  double pwm_full_us = 0.0;     ///< pulse width of duty 1 (calibrated high end point)
  double resistance_ohm = 0.0;  ///< MOSFET on-resistance and motor leads, in series with the winding

  /// Throws FieldError (esc.*) for end points outside 800..2200 us or less than 200 us apart, or a
  /// resistance outside 0..1 ohm.
  void validate() const;

  /// Duty for `pwm_us` when both end points are moved by `end_point_offset_us` (a flying ESC
  /// calibrated differently from the bench's).
  double duty(double pwm_us, double end_point_offset_us = 0.0) const;
};

}  // namespace sim
}  // namespace propulsion_estimator
