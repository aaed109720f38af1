#include "propulsion_estimator/onboard/forgetting_line_fit.h"

#include <cmath>

namespace propulsion_estimator {

void ForgettingLineFit::reset(const Eigen::Vector2d& start, const Eigen::Vector2d& prior_std, double noise_std) {
  theta_ = start;
  bound_ = prior_std.cwiseAbs2() / (noise_std * noise_std);
  p_ = bound_.asDiagonal();
}

void ForgettingLineFit::forget(double keep) {
  p_ /= keep;
  for (int k = 0; k < 2; ++k) {
    if (p_(k, k) > bound_(k)) {
      // Scaling row and column alike keeps the covariance symmetric and positive.
      const double scale = std::sqrt(bound_(k) / p_(k, k));
      p_.row(k) *= scale;
      p_.col(k) *= scale;
    }
  }
}

double ForgettingLineFit::add(double x, double y, double* innovation) {
  const Eigen::Vector2d phi(1.0, x);
  const double residual = y - phi.dot(theta_);
  const Eigen::Vector2d p_phi = p_ * phi;
  const double variance = 1.0 + phi.dot(p_phi);
  const Eigen::Vector2d gain = p_phi / variance;
  theta_ += gain * residual;
  p_ -= gain * p_phi.transpose();
  // Kept exactly symmetric: the update's two triangles round apart, and the error grows until the
  // covariance is no longer positive and the fit diverges (it did on arm64, where Eigen's products
  // round differently from x86-64's; FollowsAChangeOnlyWithForgetting failed there).
  p_ = (0.5 * (p_ + p_.transpose())).eval();
  if (innovation) *innovation = variance;
  return residual;
}

}  // namespace propulsion_estimator
