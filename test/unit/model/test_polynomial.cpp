#include <stdexcept>

#include <gtest/gtest.h>

#include "propulsion_estimator/model/polynomial_2d.h"
#include "propulsion_estimator/model/response_surface.h"

namespace pe = propulsion_estimator;

TEST(Polynomial2D, EvaluatesEachTerm) {
  const pe::Polynomial2D p({{0, 0, 1.0}, {1, 0, 2.0}, {0, 1, 3.0}, {2, 1, 0.5}});
  EXPECT_DOUBLE_EQ(p.evaluate(2.0, 3.0), 1.0 + 2.0 * 2.0 + 3.0 * 3.0 + 0.5 * 4.0 * 3.0);
  EXPECT_EQ(p.maxPwmPower(), 2);
  EXPECT_EQ(p.maxVoltagePower(), 1);
}

TEST(Polynomial2D, RefusesRepeatedAndOutOfRangePowers) {
  EXPECT_THROW(pe::Polynomial2D({{1, 0, 1.0}, {1, 0, 2.0}}), std::invalid_argument);
  EXPECT_THROW(pe::Polynomial2D({{10, 0, 1.0}}), std::invalid_argument);
  EXPECT_THROW(pe::Polynomial2D({{0, -1, 1.0}}), std::invalid_argument);
}

TEST(PolynomialBasis, MatchesMatlabPolyXY) {
  // poly21 of thesis table 5.1: p00 p10 p01 p20 p11.
  const std::vector<std::pair<int, int>> poly21 = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}};
  EXPECT_EQ(pe::polynomialBasis(2, 1), poly21);
  // poly52 of table 5.4 has 15 terms, the last being p50 p41 p32.
  const auto poly52 = pe::polynomialBasis(5, 2);
  ASSERT_EQ(poly52.size(), 15u);
  EXPECT_EQ(poly52[12], std::make_pair(5, 0));
  EXPECT_EQ(poly52[14], std::make_pair(3, 2));
  EXPECT_EQ(pe::polynomialBasis(5, 3).size(), 18u);  // i <= 5, j <= 3, i + j <= 5
}

TEST(ResponseSurface, AppliesScalingAndRatio) {
  pe::InputScaling scaling{1500.0, 400.0, 11.0, 1.0};
  const pe::ResponseSurface linear(pe::Polynomial2D({{1, 0, 2.0}, {0, 1, 1.0}}), scaling);
  EXPECT_DOUBLE_EQ(linear.evaluate(1900.0, 12.0), 2.0 * 1.0 + 1.0);
  const pe::ResponseSurface ratio(pe::Polynomial2D({{0, 0, 6.0}}), pe::Polynomial2D({{0, 0, 2.0}, {1, 0, 1.0}}), {});
  EXPECT_DOUBLE_EQ(ratio.evaluate(1.0, 0.0), 2.0);
}
