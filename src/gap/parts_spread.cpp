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
  requireWithin("parts_max_imitated_share", max_imitated_share, 0.0, 1.0);
}

namespace {

// The share of sum(change^2) that a + k * shift takes up at its least-squares best with
// |a| <= max_a and |k| <= 1 (shift: the ESCs' spread's change on each block). The problem is
// convex, so its optimum is the unconstrained one when that is inside the box, else the best of
// the four edges' one-dimensional optima.
double imitatedShare(const std::vector<double>& change, const std::vector<double>& shift, double max_a) {
  const double n = static_cast<double>(change.size());
  double sc = 0.0, ss = 0.0, scc = 0.0, sss = 0.0, scs = 0.0;
  for (std::size_t i = 0; i < change.size(); ++i) {
    sc += change[i];
    ss += shift[i];
    scc += change[i] * change[i];
    sss += shift[i] * shift[i];
    scs += change[i] * shift[i];
  }
  if (!(scc > 0.0)) return 1.0;
  const auto left = [&](double a, double k) {
    return scc + n * a * a + k * k * sss - 2.0 * a * sc - 2.0 * k * scs + 2.0 * a * k * ss;
  };
  double best = scc;
  const double det = n * sss - ss * ss;
  if (det > 1e-12 * n * sss) {
    const double a = (sc * sss - ss * scs) / det;
    const double k = (n * scs - ss * sc) / det;
    if (std::abs(a) <= max_a && std::abs(k) <= 1.0) best = std::min(best, left(a, k));
  }
  for (double a : {-max_a, max_a}) {
    const double k = sss > 0.0 ? std::clamp((scs - a * ss) / sss, -1.0, 1.0) : 0.0;
    best = std::min(best, left(a, k));
  }
  for (double k : {-1.0, 1.0}) {
    const double a = std::clamp((sc - k * ss) / n, -max_a, max_a);
    best = std::min(best, left(a, k));
  }
  return std::clamp(1.0 - best / scc, 0.0, 1.0);
}

}  // namespace

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
  std::vector<double> changes, shifts;
  for (const Block* block : blocks) {
    const double base = views.pwmView(*block, without);
    if (!(base > 0.0)) continue;
    const double signed_change = views.pwmView(*block, fitted) / base - 1.0;
    const double signed_shift = views.pwmView(*block, shifted) / base - 1.0;
    const double change = std::abs(signed_change);
    const double escs = std::abs(signed_shift);
    // A thrust loss has the law of the propellers' spread, an ESC offset that of the ESCs' (the
    // current and RPM views tell those two apart); an effect reading a signal may take up either.
    const double parts = kind == effects::Kind::kThrustLoss  ? spread.thrust_fraction
                         : kind == effects::Kind::kEscOffset ? escs
                                                             : std::max(spread.thrust_fraction, escs);
    if (!std::isfinite(change) || !std::isfinite(parts) || !std::isfinite(signed_shift)) continue;
    changes.push_back(signed_change);
    shifts.push_back(signed_shift);
    if (change > parts) ++size.blocks_beyond;
    if (100.0 * change > size.largest_change_pct) {
      size.largest_change_pct = 100.0 * change;
      size.parts_change_pct = 100.0 * parts;
    }
  }
  // A thrust loss and an ESC offset have the parts' own laws: only their size tells them apart.
  if (effects::requiredSignal(kind) != effects::Signal::kNone) {
    size.imitated_share = imitatedShare(changes, shifts, spread.thrust_fraction);
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
  // A thrust loss and an ESC offset have the parts' own laws: their shape never names them.
  if (effects::requiredSignal(kind) != effects::Signal::kNone && size.imitated_share <= spread.max_imitated_share) {
    return "";
  }
  return "not named: changes the thrust by at most " + formatPrintf("%.1f", size.largest_change_pct) +
         " % on any block (" + formatPrintf("%.1f", size.parts_change_pct) +
         " % there is what healthy rotors and ESCs differ from the bench's by: " +
         formatNumber(100.0 * spread.thrust_fraction) + " % thrust, " +
         formatNumber(spread.esc_end_point_us) + " us end points); beyond it on " +
         std::to_string(size.blocks_beyond) + " blocks, " + std::to_string(kMinBlocksBeyondParts) +
         " needed" +
         (size.imitated_share < 1.0 ? ", and they could imitate " + formatPrintf("%.0f", 100.0 * size.imitated_share) +
                                          " % of its shape (at most " +
                                          formatPrintf("%.0f", 100.0 * spread.max_imitated_share) + " % to name it)"
                                    : std::string());
}

}  // namespace gap
}  // namespace propulsion_estimator
