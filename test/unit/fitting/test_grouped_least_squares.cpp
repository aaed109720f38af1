// GroupedLeastSquares solves every candidate and fold from per-group sufficient statistics; these
// tests refit the raw rows directly (column-pivoting QR, no normal equations) and compare.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <random>
#include <vector>

#include "propulsion_estimator/fitting/grouped_least_squares.h"

namespace pe = propulsion_estimator;

namespace {

struct Rows {
  std::vector<int> group;
  std::vector<double> x, v, y;
};

// Four voltage groups of scaled inputs in [-1, 1], y a smooth surface of a few hundred units plus
// noise, so that no candidate fits exactly and every fold's error is non-trivial. Each level's
// voltages scatter by `voltage_sigma` around it, as a logged supply voltage does.
Rows sweepRows(double voltage_sigma) {
  Rows rows;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> pwm(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 1.0);
  const double levels[] = {-1.0, -0.3, 0.4, 1.0};
  for (int g = 0; g < 4; ++g) {
    for (int k = 0; k < 60 + 7 * g; ++k) {  // unequal group sizes
      const double x = pwm(random);
      const double v = levels[g] + voltage_sigma * noise(random);
      rows.group.push_back(g);
      rows.x.push_back(x);
      rows.v.push_back(v);
      rows.y.push_back(400.0 + 250.0 * x + 60.0 * x * x + 40.0 * v + 15.0 * x * v - 30.0 * std::pow(x, 3) +
                       8.0 * std::exp(x) * v + 2.0 * noise(random));
    }
  }
  return rows;
}

pe::fitting::GroupedLeastSquares accumulate(const Rows& rows, int groups, double offset) {
  pe::fitting::GroupedLeastSquares squares(groups, offset);
  for (int g = 0; g < groups; ++g) {
    std::vector<double> x, v, y;
    for (std::size_t r = 0; r < rows.y.size(); ++r) {
      if (rows.group[r] != g) continue;
      x.push_back(rows.x[r]);
      v.push_back(rows.v[r]);
      y.push_back(rows.y[r]);
    }
    // In two calls, so that accumulating one group across calls is covered too.
    const std::size_t half = y.size() / 2;
    squares.add(g, x.data(), v.data(), y.data(), half);
    squares.add(g, x.data() + half, v.data() + half, y.data() + half, y.size() - half);
  }
  return squares;
}

// The design matrix of the candidate's terms on the rows of `include`.
Eigen::MatrixXd design(const Rows& rows, const std::vector<int>& terms, const std::vector<bool>& include) {
  const std::vector<std::pair<int, int>>& basis = pe::fitting::GroupedLeastSquares::fullBasis();
  std::vector<std::size_t> selected;
  for (std::size_t r = 0; r < rows.y.size(); ++r) {
    if (include[r]) selected.push_back(r);
  }
  Eigen::MatrixXd a(selected.size(), terms.size());
  for (std::size_t i = 0; i < selected.size(); ++i) {
    for (std::size_t t = 0; t < terms.size(); ++t) {
      const auto [px, pv] = basis[terms[t]];
      a(i, t) = std::pow(rows.x[selected[i]], px) * std::pow(rows.v[selected[i]], pv);
    }
  }
  return a;
}

Eigen::VectorXd targets(const Rows& rows, const std::vector<bool>& include) {
  std::vector<double> y;
  for (std::size_t r = 0; r < rows.y.size(); ++r) {
    if (include[r]) y.push_back(rows.y[r]);
  }
  return Eigen::Map<const Eigen::VectorXd>(y.data(), y.size());
}

// Coefficients of the candidate fitted by QR on the rows outside `left_out` (-1: all rows).
Eigen::VectorXd bruteForceSolve(const Rows& rows, const std::vector<int>& terms, int left_out) {
  std::vector<bool> training(rows.y.size());
  for (std::size_t r = 0; r < rows.y.size(); ++r) training[r] = rows.group[r] != left_out;
  return design(rows, terms, training).colPivHouseholderQr().solve(targets(rows, training));
}

double bruteForceHeldOutRmse(const Rows& rows, const std::vector<int>& terms, int groups) {
  double sse = 0.0;
  for (int g = 0; g < groups; ++g) {
    const Eigen::VectorXd beta = bruteForceSolve(rows, terms, g);
    std::vector<bool> held_out(rows.y.size());
    for (std::size_t r = 0; r < rows.y.size(); ++r) held_out[r] = rows.group[r] == g;
    sse += (design(rows, terms, held_out) * beta - targets(rows, held_out)).squaredNorm();
  }
  return std::sqrt(sse / static_cast<double>(rows.y.size()));
}

}  // namespace

TEST(GroupedLeastSquares, SolveAndHeldOutRmseEqualRefitsOfTheRawRows) {
  const Rows rows = sweepRows(0.02);
  double mean = 0.0;
  for (double y : rows.y) mean += y / static_cast<double>(rows.y.size());
  const pe::fitting::GroupedLeastSquares squares = accumulate(rows, 4, mean);
  ASSERT_EQ(squares.groups(), 4);
  EXPECT_EQ(squares.rows(0), 60);
  EXPECT_EQ(squares.rows(3), 81);
  int compared = 0;
  // Four voltage levels: a fold keeps three, which determine voltage degree 2 at most.
  for (int dx = 1; dx <= 5; ++dx) {
    for (int dv = 0; dv <= 2; ++dv) {
      const std::vector<int> terms = pe::fitting::GroupedLeastSquares::subBasis(dx, dv);
      for (int left_out = -1; left_out < 4; ++left_out) {
        const std::optional<Eigen::VectorXd> beta = squares.solve(terms, left_out);
        ASSERT_TRUE(beta.has_value()) << dx << "," << dv << " without " << left_out;
        const Eigen::VectorXd expected = bruteForceSolve(rows, terms, left_out);
        // Coefficients of y in the hundreds; relative to their size.
        EXPECT_LT((*beta - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff())
            << dx << "," << dv << " without " << left_out;
      }
      const std::optional<double> rmse = squares.heldOutRmse(terms);
      ASSERT_TRUE(rmse.has_value()) << dx << "," << dv;
      const double expected = bruteForceHeldOutRmse(rows, terms, 4);
      EXPECT_NEAR(*rmse, expected, 1e-10 * expected) << dx << "," << dv;
      EXPECT_GT(expected, 1.0);  // the noise alone is 2 units: a non-trivial comparison
      ++compared;
    }
  }
  EXPECT_EQ(compared, 15);
}

TEST(GroupedLeastSquares, TheOffsetOnlyMovesTheIntercept) {
  const Rows rows = sweepRows(0.02);
  const std::vector<int> terms = pe::fitting::GroupedLeastSquares::subBasis(3, 1);
  const std::optional<Eigen::VectorXd> zero = accumulate(rows, 4, 0.0).solve(terms, 2);
  const std::optional<Eigen::VectorXd> shifted = accumulate(rows, 4, 437.5).solve(terms, 2);
  ASSERT_TRUE(zero && shifted);
  EXPECT_LT((*zero - *shifted).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(GroupedLeastSquares, AFoldThatCannotDetermineTheTermsIsSingular) {
  // Exact voltages, two levels per group.
  Rows rows = sweepRows(0.0);
  for (int& group : rows.group) group = group < 2 ? 0 : 1;
  const pe::fitting::GroupedLeastSquares squares = accumulate(rows, 2, 0.0);
  // All rows span four voltages: voltage degree 3 is determined on everything.
  ASSERT_TRUE(squares.solve(pe::fitting::GroupedLeastSquares::subBasis(2, 3)).has_value());
  // Group 0 alone holds two voltages (-1.0 and -0.3): degree 1 in v is determined without group
  // 1, degree 2 is not, and neither is its held-out error.
  EXPECT_TRUE(squares.solve(pe::fitting::GroupedLeastSquares::subBasis(2, 1), 1).has_value());
  EXPECT_FALSE(squares.solve(pe::fitting::GroupedLeastSquares::subBasis(2, 2), 1).has_value());
  EXPECT_FALSE(squares.heldOutRmse(pe::fitting::GroupedLeastSquares::subBasis(2, 2)).has_value());
}
