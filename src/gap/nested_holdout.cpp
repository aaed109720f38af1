// The nested hold-out: the flights that score the correction took no part in selecting the
// effects or fitting any parameter, the suspect motor's factor included (the rotor lag and the
// blocks' steady/dynamic split excepted: chosen once on all flights, and reused).
#include "diagnoser.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

namespace {

void rmseAndBias(const std::vector<double>& residuals, double* rmse_pct, double* bias_pct) {
  double sum = 0.0, sum2 = 0.0;
  for (double r : residuals) {
    sum += r;
    sum2 += r * r;
  }
  *rmse_pct = 100.0 * std::sqrt(sum2 / residuals.size());
  *bias_pct = 100.0 * sum / residuals.size();
}

}  // namespace

// 5. The whole diagnosis again on the units outside each outer fold, scored on that fold.
void Diagnoser::nestedHoldOut() {
  NestedHoldOut& nested = diagnosis_.heldout.nested;
  if (units_ < 3) {
    nested.unavailable = "needs three " + unit_name_ + "s or more (" + std::to_string(units_) +
                         "): the inner selection must hold one out too";
    return;
  }
  const int folds = std::min(units_, config_.nested_folds);
  const effects::ModelEffects plain = references();
  const ThrustViews plain_views(model_, motorCount(), config_.rpm_view);
  std::vector<double> before(blocks_.size()), after(blocks_.size(), kNaN);
  for (std::size_t i = 0; i < blocks_.size(); ++i) before[i] = relative(plain_views.pwmView(blocks_[i], plain), blocks_[i]);
  for (int fold = 0; fold < folds; ++fold) {
    std::vector<bool> keep(units_);
    NestedFold record;
    for (int unit = 0; unit < units_; ++unit) {
      keep[unit] = unit % folds != fold;
      (keep[unit] ? record.fitted_on : record.scored_on).push_back(unit_names_[unit]);
    }
    std::vector<bool> keep_block(blocks_.size());
    for (std::size_t i = 0; i < blocks_.size(); ++i) keep_block[i] = keep[unit_of_block_[i]];
    Diagnoser inner(*this, keep_block, plain_views);
    const effects::ModelEffects fitted = inner.selectAndFit();
    record.effects = inner.working_;
    record.suspect_channel = inner.diagnosis_.motors.suspect_channel;
    for (std::size_t i = 0; i < blocks_.size(); ++i) {
      if (!keep[unit_of_block_[i]]) after[i] = relative(inner.views_.pwmView(blocks_[i], fitted), blocks_[i]);
    }
    nested.folds.push_back(record);
  }
  rmseAndBias(before, &nested.before_rmse_pct, &nested.before_bias_pct);
  rmseAndBias(after, &nested.after_rmse_pct, &nested.after_bias_pct);
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
