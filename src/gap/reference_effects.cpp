// The effects of a vehicle's healthy flights (fitReferenceEffects) and the test that an effect
// found on other flights is a change from them (notAChange).
#include "propulsion_estimator/gap/reference_effects.h"

#include <cmath>

#include "diagnoser.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/gap/effect_fit.h"

namespace propulsion_estimator {
namespace gap {

std::string notAChange(effects::Kind kind, double value, double ci_half, double signal_median,
                       const ReferenceEffects& reference) {
  const auto found = reference.find(kind);
  if (found == reference.end()) return "";
  const ReferenceEffect& healthy = found->second;
  if (std::isfinite(healthy.signal_low) && std::isfinite(signal_median)) {
    const double width = healthy.signal_high - healthy.signal_low;
    if (signal_median < healthy.signal_low - width || signal_median > healthy.signal_high + width) return "";
  }
  const double allowed = std::hypot(ci_half, healthy.ci_half);
  if (!(std::abs(value - healthy.value) <= allowed)) return "";
  return "not named: no change from the vehicle's healthy flights (" + formatPrintf("%.4g", healthy.value) +
         " +- " + formatPrintf("%.2g", healthy.ci_half) + " there, " + formatPrintf("%.4g", value) + " +- " +
         formatPrintf("%.2g", ci_half) + " here): the vehicle's own, not what changed";
}

namespace detail {

ReferenceEffects Diagnoser::fitEachAlone() {
  config_.validate();
  cut();
  findUnits();
  balanceMotors();
  ReferenceEffects fitted;
  for (Kind kind : effects::kAllKinds) {
    if (!testability(kind).empty()) continue;
    const EffectFit fit = fitEffects(views_, all_, {kind}, references());
    ReferenceEffect effect;
    effect.value = *fit.effects.parameter(kind);
    effect.ci_half = fit.ci_half.front();
    if (!std::isfinite(effect.value) || !std::isfinite(effect.ci_half)) continue;
    const effects::Signal signal = effects::requiredSignal(kind);
    if (signal != effects::Signal::kNone) {
      for (const Block* block : all_) {
        const double read = block->signals.value(signal);
        if (!std::isfinite(read)) continue;
        effect.signal_low = std::isfinite(effect.signal_low) ? std::min(effect.signal_low, read) : read;
        effect.signal_high = std::isfinite(effect.signal_high) ? std::max(effect.signal_high, read) : read;
      }
    }
    fitted[kind] = effect;
  }
  return fitted;
}

}  // namespace detail

ReferenceEffects fitReferenceEffects(const PropulsionModel& model, const Vehicle& vehicle,
                                     const std::vector<Flight>& flights, const DiagnosisConfig& config) {
  return detail::Diagnoser(model, vehicle, flights, config, {}).fitEachAlone();
}

}  // namespace gap
}  // namespace propulsion_estimator
