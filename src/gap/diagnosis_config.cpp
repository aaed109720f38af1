#include <cmath>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/gap/diagnosis.h"
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace gap {

void DiagnosisConfig::validate() const {
  requirePositive("rotor_diameter_m", rotor_diameter_m, 3.0, " m");
  requirePositive("signal_timeout_s", signal_timeout_s, 60.0, " s");
  requirePositive("max_pwm_change_us", max_pwm_change_us, 1000.0, " us");
  requirePositive("max_accel_m_s2", max_accel_m_s2, 50.0, " m/s^2");
  if (!std::isnan(rotor_time_constant_s)) requireWithin("rotor_time_constant_s", rotor_time_constant_s, 0.0, 1.0, " s");
  requirePositive("dynamic_max_pwm_change_us", dynamic_max_pwm_change_us, 1000.0, " us");
  requirePositive("dynamic_max_accel_m_s2", dynamic_max_accel_m_s2, 50.0, " m/s^2");
  requireWithin("permutations", permutations, 20, 100000);
  requirePositive("significance", significance, 0.2);
  requireWithin("min_improvement_pct", min_improvement_pct, 0.0, 50.0, " %");
  for (const auto& [kind, points] : min_regional_improvement_pct) {
    const std::string key = "min_regional_improvement_pct." + std::string(effects::kindName(kind));
    if (!effects::describe(kind).informative) {
      throw FieldError(key, "acts on every block: it has no blocks of its own to be judged on");
    }
    requireWithin(key, points, 0.0, 50.0, " %");
  }
  for (const auto& [kind, points] : min_later_regional_improvement_pct) {
    const std::string key = "min_later_regional_improvement_pct." + std::string(effects::kindName(kind));
    const auto first_round = min_regional_improvement_pct.find(kind);
    if (first_round == min_regional_improvement_pct.end()) {
      throw FieldError(key, "needs a min_regional_improvement_pct: an effect not judged where its law acts in a first "
                            "round is not judged there after one");
    }
    requireWithin(key, points, 0.0, 50.0, " %");
    if (points < first_round->second) {
      throw FieldError(key, formatNumber(points) + " % is below min_regional_improvement_pct." +
                                std::string(effects::kindName(kind)) + " (" + formatNumber(first_round->second) +
                                " %): what an earlier law leaves there is no less than what the model family's "
                                "mismatch gives");
    }
  }
  requireWithin("max_mean_square_ratio", max_mean_square_ratio, 0.0, 1.0);
  requireWithin("ambiguity_p", ambiguity_p, 0.0, 1.0);
  requireWithin("nested_folds", nested_folds, 2, 100);
  requireWithin("motor_min_gap", motor_min_gap, 0.0, 1.0);
  requireWithin("motor_healthy_gap_std", motor_healthy_gap_std, 0.0, 1.0);
  parts_spread.validate();
  if (motor_reference) motor_reference->validate();
}

}  // namespace gap
}  // namespace propulsion_estimator
