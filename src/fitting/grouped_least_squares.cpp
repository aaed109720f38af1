#include "propulsion_estimator/fitting/grouped_least_squares.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "propulsion_estimator/model/polynomial_2d.h"

namespace propulsion_estimator {
namespace fitting {
namespace {

// Rows turned into basis rows and added as one rank update.
constexpr std::size_t kChunkRows = 256;
// A pivot of the normal matrix this small relative to the largest means the candidate's terms
// are not determined by the data (the inputs are scaled to [-1, 1], so this is a rank test).
constexpr double kRelativePivot = 1e-12;

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::MatrixXd subMatrix(const Eigen::MatrixXd& full, const std::vector<int>& terms) {
  const int n = static_cast<int>(terms.size());
  Eigen::MatrixXd sub(n, n);
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) sub(a, b) = full(terms[a], terms[b]);
  }
  return sub;
}

Eigen::VectorXd subVector(const Eigen::VectorXd& full, const std::vector<int>& terms) {
  Eigen::VectorXd sub(terms.size());
  for (std::size_t a = 0; a < terms.size(); ++a) sub(a) = full(terms[a]);
  return sub;
}

}  // namespace

const std::vector<std::pair<int, int>>& GroupedLeastSquares::fullBasis() {
  static const std::vector<std::pair<int, int>> basis = polynomialBasis(kMaxPwmDegree, kMaxVoltageDegree);
  return basis;
}

std::vector<int> GroupedLeastSquares::subBasis(int pwm_degree, int voltage_degree) {
  const std::vector<std::pair<int, int>>& full = fullBasis();
  std::vector<int> terms;
  for (const auto& term : polynomialBasis(pwm_degree, voltage_degree)) {
    terms.push_back(static_cast<int>(std::find(full.begin(), full.end(), term) - full.begin()));
  }
  return terms;
}

GroupedLeastSquares::GroupedLeastSquares(int groups, double y_offset)
    : y_offset_(y_offset),
      xtx_(groups, Eigen::MatrixXd::Zero(fullBasis().size(), fullBasis().size())),
      xty_(groups, Eigen::VectorXd::Zero(fullBasis().size())),
      yty_(groups, 0.0),
      count_(groups, 0),
      total_xtx_(Eigen::MatrixXd::Zero(fullBasis().size(), fullBasis().size())),
      total_xty_(Eigen::VectorXd::Zero(fullBasis().size())) {}

void GroupedLeastSquares::add(int group, const double* x, const double* v, const double* y, std::size_t count) {
  const std::vector<std::pair<int, int>>& basis = fullBasis();
  const int terms = static_cast<int>(basis.size());
  RowMajorMatrix chunk(kChunkRows, terms);
  Eigen::VectorXd targets(kChunkRows);
  Eigen::MatrixXd lower = Eigen::MatrixXd::Zero(terms, terms);
  Eigen::VectorXd xty = Eigen::VectorXd::Zero(terms);
  double yty = 0.0;
  for (std::size_t start = 0; start < count; start += kChunkRows) {
    const std::size_t n = std::min(kChunkRows, count - start);
    for (std::size_t r = 0; r < n; ++r) {
      double x_pow[kMaxPwmDegree + 1];
      double v_pow[kMaxVoltageDegree + 1];
      x_pow[0] = 1.0;
      v_pow[0] = 1.0;
      for (int i = 1; i <= kMaxPwmDegree; ++i) x_pow[i] = x_pow[i - 1] * x[start + r];
      for (int j = 1; j <= kMaxVoltageDegree; ++j) v_pow[j] = v_pow[j - 1] * v[start + r];
      for (int t = 0; t < terms; ++t) chunk(r, t) = x_pow[basis[t].first] * v_pow[basis[t].second];
      targets(r) = y[start + r] - y_offset_;
    }
    const auto rows = chunk.topRows(n);
    const auto ys = targets.head(n);
    lower.selfadjointView<Eigen::Lower>().rankUpdate(rows.transpose());
    xty.noalias() += rows.transpose() * ys;
    yty += ys.squaredNorm();
  }
  const Eigen::MatrixXd full = lower.selfadjointView<Eigen::Lower>();
  xtx_[group] += full;
  xty_[group] += xty;
  yty_[group] += yty;
  count_[group] += static_cast<long>(count);
  total_xtx_ += full;
  total_xty_ += xty;
}

std::optional<Eigen::VectorXd> GroupedLeastSquares::solveCentred(const std::vector<int>& terms, int left_out) const {
  Eigen::MatrixXd normal = subMatrix(total_xtx_, terms);
  Eigen::VectorXd right = subVector(total_xty_, terms);
  if (left_out >= 0) {
    normal -= subMatrix(xtx_[left_out], terms);
    right -= subVector(xty_[left_out], terms);
  }
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(normal);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return std::nullopt;
  const Eigen::VectorXd pivots = ldlt.vectorD().cwiseAbs();
  if (!(pivots.minCoeff() > kRelativePivot * pivots.maxCoeff())) return std::nullopt;
  return Eigen::VectorXd(ldlt.solve(right));
}

std::optional<Eigen::VectorXd> GroupedLeastSquares::solve(const std::vector<int>& terms, int left_out) const {
  std::optional<Eigen::VectorXd> coefficients = solveCentred(terms, left_out);
  if (coefficients) (*coefficients)(0) += y_offset_;  // every sub-basis starts with the constant term
  return coefficients;
}

std::optional<double> GroupedLeastSquares::heldOutRmse(const std::vector<int>& terms) const {
  double sse = 0.0;
  long rows = 0;
  for (int group = 0; group < groups(); ++group) {
    if (count_[group] == 0) continue;
    const std::optional<Eigen::VectorXd> beta = solveCentred(terms, group);
    if (!beta) return std::nullopt;
    const Eigen::MatrixXd xtx = subMatrix(xtx_[group], terms);
    const Eigen::VectorXd xty = subVector(xty_[group], terms);
    // Sum of squared residuals of the held-out rows, from their sufficient statistics.
    sse += std::max(0.0, yty_[group] - 2.0 * beta->dot(xty) + beta->dot(xtx * *beta));
    rows += count_[group];
  }
  return std::sqrt(sse / static_cast<double>(rows));
}

std::optional<double> GroupedLeastSquares::heldOutRmseOf(const std::vector<int>& terms, int group) const {
  if (count_[group] == 0) return std::nullopt;
  const std::optional<Eigen::VectorXd> beta = solveCentred(terms, group);
  if (!beta) return std::nullopt;
  const Eigen::MatrixXd xtx = subMatrix(xtx_[group], terms);
  const Eigen::VectorXd xty = subVector(xty_[group], terms);
  const double sse = std::max(0.0, yty_[group] - 2.0 * beta->dot(xty) + beta->dot(xtx * *beta));
  return std::sqrt(sse / static_cast<double>(count_[group]));
}

GroupedLeastSquares GroupedLeastSquares::merged(const std::vector<int>& new_group_of, int groups) const {
  GroupedLeastSquares result(groups, y_offset_);
  for (int g = 0; g < this->groups(); ++g) {
    const int to = new_group_of[g];
    result.xtx_[to] += xtx_[g];
    result.xty_[to] += xty_[g];
    result.yty_[to] += yty_[g];
    result.count_[to] += count_[g];
  }
  result.total_xtx_ = total_xtx_;
  result.total_xty_ = total_xty_;
  return result;
}

}  // namespace fitting
}  // namespace propulsion_estimator
