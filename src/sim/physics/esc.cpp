#include "propulsion_estimator/sim/physics/esc.h"

#include <algorithm>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace sim {

void EscParams::validate() const {
  requireWithin("esc.pwm_zero_us", pwm_zero_us, 800.0, 2200.0, " us");
  requireWithin("esc.pwm_full_us", pwm_full_us, 800.0, 2200.0, " us");
  if (!(pwm_full_us - pwm_zero_us >= 200.0)) {
    throw FieldError("esc.pwm_full_us", formatNumber(pwm_full_us) + " must be at least 200 us above pwm_zero_us (" +
                                            formatNumber(pwm_zero_us) + ")");
  }
  requireWithin("esc.resistance_ohm", resistance_ohm, 0.0, 1.0, " ohm");
}

double EscParams::duty(double pwm_us, double end_point_offset_us) const {
  const double fraction = (pwm_us - pwm_zero_us - end_point_offset_us) / (pwm_full_us - pwm_zero_us);
  return std::clamp(fraction, 0.0, 1.0);
}

}  // namespace sim
}  // namespace propulsion_estimator
