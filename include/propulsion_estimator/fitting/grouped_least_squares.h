#pragma once

#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

namespace propulsion_estimator {
namespace fitting {

/// Least squares of one output on the full polyXY basis of degree (5, 3) in scaled inputs, kept
/// as per-group sufficient statistics (X'X, X'y, y'y, n). Any sub-basis (a candidate degree
/// pair) is then solved, and cross-validated with one group held out at a time, from small
/// sub-blocks of these matrices: the raw rows are read once, whatever the number of candidates
/// and folds.
class GroupedLeastSquares {
 public:
  static constexpr int kMaxPwmDegree = 5;  ///< highest PWM degree of the full basis
  static constexpr int kMaxVoltageDegree = 3;  ///< highest voltage degree of the full basis

  /// `y_offset` is subtracted from every y before accumulation (keeps y'y small, so that
  /// y'y - 2 b'X'y + b'X'Xb loses no digits); it returns in the intercept.
  GroupedLeastSquares(int groups, double y_offset);

  /// Adds rows x, v (already scaled) and y of one group.
  void add(int group, const double* x, const double* v, const double* y, std::size_t count);

  /// Indices into fullBasis() of the terms of polynomialBasis(pwm_degree, voltage_degree).
  static std::vector<int> subBasis(int pwm_degree, int voltage_degree);
  /// The (PWM power, voltage power) of each term of the full basis.
  static const std::vector<std::pair<int, int>>& fullBasis();

  /// Coefficients of the sub-basis fitted on all groups but `left_out` (-1: all groups), with the
  /// offset restored in the intercept (the first term); nullopt when the normal matrix is
  /// numerically singular.
  std::optional<Eigen::VectorXd> solve(const std::vector<int>& terms, int left_out = -1) const;

  /// Root mean square error of predicting each group from the others, pooled over all rows;
  /// nullopt when a fold's fit is singular.
  std::optional<double> heldOutRmse(const std::vector<int>& terms) const;

  /// Number of groups (folds).
  int groups() const { return static_cast<int>(count_.size()); }
  /// Rows added to `group`.
  long rows(int group) const { return count_[group]; }

 private:
  /// Normal equations of the sub-basis on all groups but `left_out`, solved for centred y.
  std::optional<Eigen::VectorXd> solveCentred(const std::vector<int>& terms, int left_out) const;

  double y_offset_;
  std::vector<Eigen::MatrixXd> xtx_;  ///< full symmetric
  std::vector<Eigen::VectorXd> xty_;
  std::vector<double> yty_;
  std::vector<long> count_;
  Eigen::MatrixXd total_xtx_;
  Eigen::VectorXd total_xty_;
};

}  // namespace fitting
}  // namespace propulsion_estimator
