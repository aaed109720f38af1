#include "propulsion_estimator/gap/parts_spread.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace gap {

void PartsSpread::validate() const {
  requireWithin("parts_thrust_spread", thrust_fraction, 0.0, 0.5);
  requireWithin("parts_esc_spread_us", esc_end_point_us, 0.0, 100.0, " us");
}

EffectSize effectSizeAgainstParts(const ThrustViews& views, const std::vector<const Block*>& blocks,
                                  const effects::ModelEffects& fitted, effects::Kind kind,
                                  const PartsSpread& spread) {
  effects::ModelEffects without = fitted;
  without.setParameter(kind, std::nullopt);
  // The ESCs' spread acts on top of whatever ESC offset the other effects already hold.
  effects::ModelEffects shifted = without;
  shifted.setParameter(effects::Kind::kEscOffset,
                       without.parameter(effects::Kind::kEscOffset).value_or(0.0) + spread.esc_end_point_us);
  EffectSize size;
  for (const Block* block : blocks) {
    const double base = views.pwmView(*block, without);
    if (!(base > 0.0)) continue;
    const double change = std::abs(views.pwmView(*block, fitted) / base - 1.0);
    const double escs = std::abs(views.pwmView(*block, shifted) / base - 1.0);
    // A thrust loss has the law of the propellers' spread, an ESC offset that of the ESCs' (the
    // current and RPM views tell those two apart); an effect reading a signal may take up either.
    const double parts = kind == effects::Kind::kThrustLoss  ? spread.thrust_fraction
                         : kind == effects::Kind::kEscOffset ? escs
                                                             : std::max(spread.thrust_fraction, escs);
    if (!std::isfinite(change) || !std::isfinite(parts)) continue;
    if (change > parts) ++size.blocks_beyond;
    if (100.0 * change > size.largest_change_pct) {
      size.largest_change_pct = 100.0 * change;
      size.parts_change_pct = 100.0 * parts;
    }
  }
  return size;
}

std::string withinPartsSpread(effects::Kind kind, double parameter, const EffectSize& size, const PartsSpread& spread) {
  if (kind == effects::Kind::kThrustLoss && parameter < -spread.thrust_fraction) {
    return "not named: a thrust gain of " + formatPrintf("%.1f", -100.0 * parameter) +
           " %, which blockage and rotor interaction cannot give (healthy rotors differ from the bench's by " +
           formatPrintf("%.1f", 100.0 * spread.thrust_fraction) +
           " %): what another effect's law leaves over, or a bench unit weaker than the vehicle's";
  }
  if (size.blocks_beyond >= kMinBlocksBeyondParts) return "";
  return "not named: changes the thrust by at most " + formatPrintf("%.1f", size.largest_change_pct) +
         " % on any block (" + formatPrintf("%.1f", size.parts_change_pct) +
         " % there is what healthy rotors and ESCs differ from the bench's by: " +
         formatNumber(100.0 * spread.thrust_fraction) + " % thrust, " +
         formatNumber(spread.esc_end_point_us) + " us end points); beyond it on " +
         std::to_string(size.blocks_beyond) + " blocks, " + std::to_string(kMinBlocksBeyondParts) + " needed";
}

}  // namespace gap
}  // namespace propulsion_estimator
