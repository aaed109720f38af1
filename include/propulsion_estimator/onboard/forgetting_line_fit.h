#pragma once

#include <Eigen/Core>

namespace propulsion_estimator {

/// y = offset + slope x by recursive least squares with exponential forgetting, as autopilots
/// estimate their battery's resistance (PX4's battery estimator does the same). Each variance is
/// bounded by the prior's, so that a long stretch without excitation (a steady hover) does not wind
/// the covariance up. Units are the caller's: y's, and y's per x. O(1), no allocation.
class ForgettingLineFit {
 public:
  /// Starts at `start` (offset, slope) with the prior standard deviations `prior_std` (of offset
  /// and slope) for readings of noise `noise_std` (> 0). Throws nothing.
  void reset(const Eigen::Vector2d& start, const Eigen::Vector2d& prior_std, double noise_std);
  /// Ages the fit by `keep` (0..1, exp(-dt / memory)): older readings weigh less.
  void forget(double keep) { forget(keep, keep); }
  /// Ages the offset by `keep_offset` and the slope by `keep_slope` (0..1 each): a slope the
  /// readings no longer excite (x steady) is kept while the offset follows y.
  void forget(double keep_offset, double keep_slope);
  /// Takes the reading `y` at `x`. Returns its residual before the update; `innovation` (if given)
  /// receives the residual's variance relative to the noise's (>= 1).
  double add(double x, double y, double* innovation = nullptr);
  /// Takes the reading `y` at `x` with the slope held as it is (a reading that cannot tell the
  /// slope from the offset): only the offset and its variance move. Returns the residual.
  double addWithSlopeHeld(double x, double y);

  /// Offset and slope.
  const Eigen::Vector2d& parameters() const { return theta_; }
  /// Offset and slope, for a caller whose model moves them between readings.
  Eigen::Vector2d& parameters() { return theta_; }
  /// Their covariance relative to the noise's variance (multiply by noise_std^2).
  const Eigen::Matrix2d& covariance() const { return p_; }

 private:
  Eigen::Vector2d theta_ = Eigen::Vector2d::Zero();
  Eigen::Matrix2d p_ = Eigen::Matrix2d::Zero();
  Eigen::Vector2d bound_ = Eigen::Vector2d::Zero();  // the prior's variances, relative
};

}  // namespace propulsion_estimator
