// The joint error of both views, on which the selection's comparisons and tests run: the PWM
// view's and the current view's held-out residuals, each weighed by what it knows.
#include "diagnoser.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

// The two views err by noise of very different sizes: the battery current through the inverted
// current surface scatters several times more from block to block than the PWM view. Summed with
// equal weights, the current view's scatter would outvote a clear verdict of the PWM view; weighed
// by the inverse of each view's noise variance, as a likelihood weighs them, each view counts by
// what it knows. The noise is the scatter between neighbouring blocks of one stretch (half the
// mean squared difference), which a slowly varying gap, the thing to explain, hardly enters.
double Diagnoser::currentViewWeight(const HeldOutPrediction& before) const {
  double sum_pwm = 0.0, sum_current = 0.0;
  int pairs = 0;
  for (std::size_t i = 1; i < blocks_.size(); ++i) {
    if (blocks_[i].flight != blocks_[i - 1].flight || blocks_[i].group != blocks_[i - 1].group) continue;
    const double d_current = before.current[i] - before.current[i - 1];
    if (!std::isfinite(d_current)) continue;
    const double d_pwm = before.pwm[i] - before.pwm[i - 1];
    sum_pwm += d_pwm * d_pwm;
    sum_current += d_current * d_current;
    ++pairs;
  }
  if (pairs < 2 || !(sum_current > 0.0) || !(sum_pwm > 0.0)) return 1.0;
  return sum_pwm / sum_current;
}

double Diagnoser::jointMeanSquare(const HeldOutPrediction& prediction) const {
  const double weight = diagnosis_.current_view_weight;
  double sum = 0.0;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    sum += prediction.pwm[i] * prediction.pwm[i];
    if (std::isfinite(prediction.current[i])) sum += weight * prediction.current[i] * prediction.current[i];
  }
  return sum / blocks_.size();
}

std::vector<double> Diagnoser::groupImprovements(const HeldOutPrediction& before, const HeldOutPrediction& after) const {
  const double weight = diagnosis_.current_view_weight;
  std::map<std::pair<int, int>, double> groups;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    double d = before.pwm[i] * before.pwm[i] - after.pwm[i] * after.pwm[i];
    if (std::isfinite(before.current[i]) && std::isfinite(after.current[i])) {
      d += weight * (before.current[i] * before.current[i] - after.current[i] * after.current[i]);
    }
    groups[{blocks_[i].flight, blocks_[i].group}] += d;
  }
  std::vector<double> improvements;
  for (const auto& entry : groups) improvements.push_back(entry.second);
  return improvements;
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
