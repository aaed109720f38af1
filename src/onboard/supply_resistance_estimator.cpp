#include "propulsion_estimator/onboard/supply_resistance_estimator.h"

#include <algorithm>
#include <cmath>

namespace propulsion_estimator {
namespace {

// The prior: an offset within a volt (divider errors of a few percent of a 6S pack), a resistance
// within 0.2 ohm (a long thin lead and a bad connector).
constexpr double kPriorOffsetStdV = 1.0;
constexpr double kPriorResistanceStdOhm = 0.2;

}  // namespace

SupplyResistanceEstimator::SupplyResistanceEstimator(double memory_s, double voltage_sigma_v)
    : memory_s_(memory_s), sigma2_(voltage_sigma_v * voltage_sigma_v) {
  reset();
}

void SupplyResistanceEstimator::reset() {
  fit_.reset(Eigen::Vector2d::Zero(), Eigen::Vector2d(kPriorOffsetStdV, kPriorResistanceStdOhm), std::sqrt(sigma2_));
  last_time_s_ = kNaN;
  samples_ = 0;
  residual2_sum_ = 0.0;
  weight_sum_ = 0.0;
}

void SupplyResistanceEstimator::add(double time_s, double drop_v, double current_a) {
  if (!std::isfinite(time_s) || !std::isfinite(drop_v) || !std::isfinite(current_a)) return;
  if (!std::isnan(last_time_s_) && !(time_s > last_time_s_)) return;
  if (!std::isnan(last_time_s_)) {
    const double keep = std::exp(-(time_s - last_time_s_) / memory_s_);
    fit_.forget(keep);
    residual2_sum_ *= keep;
    weight_sum_ *= keep;
  }
  last_time_s_ = time_s;
  double innovation = 1.0;
  const double residual = fit_.add(current_a, drop_v, &innovation);
  // The residuals' own spread over the memory (normalised by the innovation's variance), where
  // it exceeds the assumed noise.
  residual2_sum_ += residual * residual / innovation;
  weight_sum_ += 1.0;
  ++samples_;
}

double SupplyResistanceEstimator::resistanceOhm() const { return samples_ < 2 ? kNaN : fit_.parameters()(1); }

double SupplyResistanceEstimator::resistanceStdOhm() const {
  if (samples_ < 2) return kNaN;
  return std::sqrt(std::max(0.0, fit_.covariance()(1, 1)) * std::max(sigma2_, residual2_sum_ / weight_sum_));
}

}  // namespace propulsion_estimator
