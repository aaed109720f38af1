#pragma once

#include <map>
#include <string>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/model/model_effects.h"

namespace propulsion_estimator {
namespace gap {

/// An effect as a vehicle's healthy flights show it (diagnose_gap --reference): real vehicles
/// always warm their motors, fly in the day's air and near the ground, so an effect the bench
/// model leaves out is often present on the healthy flights too, and is then no change.
struct ReferenceEffect {
  /// The effect's parameter fitted there on top of the day's air (its ParameterSpec unit).
  double value = 0.0;
  /// Its 95 % half-width; for an effect whose signal changes mostly between flights (the day's
  /// air), the larger of the fit's and the flights' jackknife (each flight left out in turn).
  double ci_half = 0.0;
  /// The lowest value of the signal the effect reads over the blocks it was fitted on; NaN for an
  /// effect reading none.
  double signal_low = kNaN;
  double signal_high = kNaN;  ///< the highest, likewise
};

/// Per effect that could be fitted on the healthy flights.
using ReferenceEffects = std::map<effects::Kind, ReferenceEffect>;

/// Why effect `kind`, fitted at `value` +- `ci_half` on flights whose blocks read its signal at
/// `signal_median` (NaN for an effect reading none), is no change from the healthy flights: its
/// parameter there lies within the two intervals combined (root sum of squares). "" when it is a
/// change, when the healthy flights do not hold the effect, or when they never flew where these
/// flights do: the median beyond their range by more than the range's width (a high site's air
/// against the day's air of home), so they cannot vouch for it there.
std::string notAChange(effects::Kind kind, double value, double ci_half, double signal_median,
                       const ReferenceEffects& reference);

/// Whether effect `kind`, found on flights whose blocks hold `between_flight_share` of its
/// signal's variance between the flights' means (NaN without the signal), is judged by its change
/// from the healthy flights alone (notAChange) and not also against healthy parts' spread: with the
/// effect in `reference`, for a signal the vehicle's state sets apart from its thrust (height,
/// speeds, the motors' temperature) that changes mostly within flights. Not for an effect reading
/// none or the battery current, nor for the day's air.
bool judgedByReferenceAlone(effects::Kind kind, const ReferenceEffects& reference, double between_flight_share);

}  // namespace gap
}  // namespace propulsion_estimator
