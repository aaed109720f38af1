// The test of improvement a candidate must pass to be named: its held-out error lower by the
// sign-flip test, and falling by more than a mismatch of model family alone gives, over all
// blocks or where its law acts.
#include "diagnoser.h"

#include <cmath>

namespace propulsion_estimator {
namespace gap {
namespace detail {

double Diagnoser::improvementPValue(const HeldOutPrediction& base, const HeldOutPrediction& with, Kind kind) const {
  return signFlipPValue(groupImprovements(base, with), config_.permutations, config_.seed + static_cast<unsigned>(kind));
}

bool Diagnoser::improvesEnough(const HeldOutPrediction& base, const HeldOutPrediction& with, double p_value,
                               std::optional<Kind> kind) const {
  if (kind) return improvesEnough(base, with, p_value, *kind, regionalError(*kind, base, with));
  return significantlyLower(base, with, p_value) && fallsOverAll(base, with);
}

bool Diagnoser::improvesEnough(const HeldOutPrediction& base, const HeldOutPrediction& with, double p_value, Kind kind,
                               const RegionalError& regional) const {
  return significantlyLower(base, with, p_value) &&
         (fallsOverAll(base, with) || fallsWhereItActs(kind, regional, config_.min_regional_improvement_pct));
}

bool Diagnoser::significantlyLower(const HeldOutPrediction& base, const HeldOutPrediction& with, double p_value) const {
  return p_value < config_.significance && jointMeanSquare(with) < jointMeanSquare(base);
}

bool Diagnoser::fallsOverAll(const HeldOutPrediction& base, const HeldOutPrediction& with) const {
  const auto rmse_pct = [](const std::vector<double>& view) { return 100.0 * std::sqrt(finiteMeanSquare(view)); };
  return fallsEnough(rmse_pct(base.pwm), rmse_pct(with.pwm)) || fallsEnough(rmse_pct(base.rpm), rmse_pct(with.rpm));
}

// Whether a view's held-out RMSE (% of the truth) falls from `before` to `after` by more than a
// mismatch of model family alone gives on null flights: in points and as a share of its square.
bool Diagnoser::fallsBy(double before_pct, double after_pct, double min_points) const {
  return std::isfinite(before_pct) && std::isfinite(after_pct) && before_pct - after_pct > min_points &&
         after_pct * after_pct < config_.max_mean_square_ratio * before_pct * before_pct;
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
