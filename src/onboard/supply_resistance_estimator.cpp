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
  theta_.setZero();
  p_ = Eigen::Vector2d(kPriorOffsetStdV * kPriorOffsetStdV, kPriorResistanceStdOhm * kPriorResistanceStdOhm)
           .asDiagonal() *
       (1.0 / sigma2_);
  last_time_s_ = kNaN;
  samples_ = 0;
  residual2_sum_ = 0.0;
  weight_sum_ = 0.0;
}

void SupplyResistanceEstimator::add(double time_s, double drop_v, double current_a) {
  if (!std::isfinite(time_s) || !std::isfinite(drop_v) || !std::isfinite(current_a)) return;
  if (!std::isnan(last_time_s_) && !(time_s > last_time_s_)) return;
  if (!std::isnan(last_time_s_)) {
    const double forget = std::exp(-(time_s - last_time_s_) / memory_s_);
    p_ /= forget;
    // Bounded by the prior: a steady current must not wind the covariance up.
    const Eigen::Vector2d bound(kPriorOffsetStdV * kPriorOffsetStdV / sigma2_,
                                kPriorResistanceStdOhm * kPriorResistanceStdOhm / sigma2_);
    for (int k = 0; k < 2; ++k) {
      if (p_(k, k) > bound(k)) {
        const double scale = std::sqrt(bound(k) / p_(k, k));
        p_.row(k) *= scale;
        p_.col(k) *= scale;
      }
    }
    residual2_sum_ *= forget;
    weight_sum_ *= forget;
  }
  last_time_s_ = time_s;
  const Eigen::Vector2d phi(1.0, current_a);
  const double residual = drop_v - phi.dot(theta_);
  const Eigen::Vector2d p_phi = p_ * phi;
  const double innovation = 1.0 + phi.dot(p_phi);
  const Eigen::Vector2d gain = p_phi / innovation;
  theta_ += gain * residual;
  p_ -= gain * p_phi.transpose();
  // The residuals' own spread over the memory (normalised by the innovation's variance), where
  // it exceeds the assumed noise.
  residual2_sum_ += residual * residual / innovation;
  weight_sum_ += 1.0;
  ++samples_;
}

double SupplyResistanceEstimator::resistanceOhm() const { return samples_ < 2 ? kNaN : theta_(1); }

double SupplyResistanceEstimator::resistanceStdOhm() const {
  if (samples_ < 2) return kNaN;
  return std::sqrt(std::max(0.0, p_(1, 1)) * std::max(sigma2_, residual2_sum_ / weight_sum_));
}

}  // namespace propulsion_estimator
