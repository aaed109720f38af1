#include "propulsion_estimator/sim/physics/sim_params.h"

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace sim {

void BenchParams::validate() const {
  air.validate("bench.air");
  if (!(sweep_pwm_min_us >= 800.0 && sweep_pwm_max_us <= 2200.0 && sweep_pwm_min_us < sweep_pwm_max_us)) {
    throw FieldError("bench.sweep_pwm_us", "[" + formatNumber(sweep_pwm_min_us) + ", " +
                                               formatNumber(sweep_pwm_max_us) + "] is not a range within 800..2200 us");
  }
  sensors.validate();
}

void SimParams::validate() const {
  chain.validate();
  battery.validate();
  bench.validate();
}

}  // namespace sim
}  // namespace propulsion_estimator
