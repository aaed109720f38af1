#include "propulsion_estimator/onboard/forgetting_line_fit.h"

#include <cmath>

namespace propulsion_estimator {

void ForgettingLineFit::reset(const Eigen::Vector2d& start, const Eigen::Vector2d& prior_std, double noise_std) {
  theta_ = start;
  bound_ = prior_std.cwiseAbs2() / (noise_std * noise_std);
  p_ = bound_.asDiagonal();
}

void ForgettingLineFit::forget(double keep_offset, double keep_slope) {
  // D P D with D = diag(1 / sqrt(keep)): symmetric and positive as P is.
  const Eigen::Vector2d d(1.0 / std::sqrt(keep_offset), 1.0 / std::sqrt(keep_slope));
  p_ = (d.asDiagonal() * p_ * d.asDiagonal()).eval();
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

double ForgettingLineFit::addWithSlopeHeld(double x, double y) {
  const double residual = y - theta_(0) - theta_(1) * x;
  // The Kalman gain of the offset alone (the slope a considered, not estimated, parameter): the
  // offset's row and column shrink, the slope's variance stays.
  const double gain = p_(0, 0) / (1.0 + p_(0, 0));
  theta_(0) += gain * residual;
  const double shrink = 1.0 - gain;
  p_(0, 0) *= shrink;
  p_(0, 1) *= shrink;
  p_(1, 0) *= shrink;
  return residual;
}

}  // namespace propulsion_estimator
