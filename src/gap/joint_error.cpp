// The joint error of the views, on which the selection's comparisons and tests run: the PWM view's,
// the current view's and the RPM view's held-out residuals, each weighed by what it knows.
#include "diagnoser.h"

#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace propulsion_estimator {
namespace gap {
namespace detail {

// The views err by noise of very different sizes: the battery current through the inverted
// current surface scatters several times more from block to block than the PWM view. Summed with
// equal weights, the current view's scatter would outvote a clear verdict of the PWM view; weighed
// by the inverse of each view's noise variance, as a likelihood weighs them, each view counts by
// what it knows. The noise is the scatter between neighbouring blocks of one stretch (half the
// mean squared difference), which a slowly varying gap, the thing to explain, hardly enters.
double Diagnoser::viewWeight(const HeldOutPrediction& before, const std::vector<double>& view) const {
  double sum_pwm = 0.0, sum_view = 0.0;
  int pairs = 0;
  for (std::size_t i = 1; i < blocks_.size(); ++i) {
    if (blocks_[i].flight != blocks_[i - 1].flight || blocks_[i].group != blocks_[i - 1].group) continue;
    const double d_view = view[i] - view[i - 1];
    if (!std::isfinite(d_view)) continue;
    const double d_pwm = before.pwm[i] - before.pwm[i - 1];
    sum_pwm += d_pwm * d_pwm;
    sum_view += d_view * d_view;
    ++pairs;
  }
  if (pairs < 2 || !(sum_view > 0.0) || !(sum_pwm > 0.0)) return 1.0;
  return sum_pwm / sum_view;
}

double Diagnoser::jointSquare(const HeldOutPrediction& prediction, std::size_t block) const {
  double square = prediction.pwm[block] * prediction.pwm[block];
  const double current = prediction.current[block], rpm = prediction.rpm[block];
  if (std::isfinite(current)) square += diagnosis_.current_view_weight * current * current;
  if (std::isfinite(rpm)) square += diagnosis_.rpm_view_weight * rpm * rpm;
  return square;
}

double Diagnoser::jointMeanSquare(const HeldOutPrediction& prediction) const {
  double sum = 0.0;
  for (std::size_t i = 0; i < blocks_.size(); ++i) sum += jointSquare(prediction, i);
  return sum / blocks_.size();
}

// What a correction explains between flights (one factor per flight: the day's air, a payload's
// hang) and what it explains within them (a motor warming over each flight) are told apart by
// taking each flight's mean residual out of each view first.
double Diagnoser::withinFlightMeanSquare(const HeldOutPrediction& prediction) const {
  const std::array<const std::vector<double>*, 3> views = {&prediction.pwm, &prediction.current, &prediction.rpm};
  const std::array<double, 3> weights = {1.0, diagnosis_.current_view_weight, diagnosis_.rpm_view_weight};
  struct Mean {
    double sum = 0.0;
    int count = 0;
  };
  std::map<std::pair<int, int>, Mean> means;  // by flight and view
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    for (int v = 0; v < 3; ++v) {
      const double residual = (*views[v])[i];
      if (!std::isfinite(residual)) continue;
      Mean& mean = means[{blocks_[i].flight, v}];
      mean.sum += residual;
      ++mean.count;
    }
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    for (int v = 0; v < 3; ++v) {
      const double residual = (*views[v])[i];
      if (!std::isfinite(residual)) continue;
      const Mean& mean = means.at({blocks_[i].flight, v});
      const double deviation = residual - mean.sum / mean.count;
      sum += weights[v] * deviation * deviation;
    }
  }
  return sum / blocks_.size();
}

// A view missing in one prediction and not the other (an offset the current view cannot match)
// would count as a fall; the block then compares in the views both have.
std::vector<double> Diagnoser::groupImprovements(const HeldOutPrediction& before, const HeldOutPrediction& after) const {
  const auto fall = [](double from, double to) {
    return std::isfinite(from) && std::isfinite(to) ? from * from - to * to : 0.0;
  };
  std::map<std::pair<int, int>, double> groups;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const double d = fall(before.pwm[i], after.pwm[i]) +
                     diagnosis_.current_view_weight * fall(before.current[i], after.current[i]) +
                     diagnosis_.rpm_view_weight * fall(before.rpm[i], after.rpm[i]);
    groups[{blocks_[i].flight, blocks_[i].group}] += d;
  }
  std::vector<double> improvements;
  for (const auto& entry : groups) improvements.push_back(entry.second);
  return improvements;
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
