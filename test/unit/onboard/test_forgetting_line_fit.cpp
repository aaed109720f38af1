// The forgetting line fit both battery estimators share: it finds a line, follows a change of it
// with forgetting, and a stretch without excitation does not wind its covariance past the prior.
#include <gtest/gtest.h>

#include <cmath>

#include "propulsion_estimator/onboard/forgetting_line_fit.h"

namespace pe = propulsion_estimator;

TEST(ForgettingLineFit, FindsTheLineFromVaryingReadings) {
  pe::ForgettingLineFit fit;
  fit.reset(Eigen::Vector2d::Zero(), Eigen::Vector2d(10.0, 1.0), 0.01);
  for (int k = 0; k < 200; ++k) {
    const double x = 5.0 + 4.0 * std::sin(0.1 * k);
    fit.add(x, 2.0 + 0.5 * x);
  }
  EXPECT_NEAR(fit.parameters()(0), 2.0, 1e-3);
  EXPECT_NEAR(fit.parameters()(1), 0.5, 1e-3);
  double innovation = 0.0;
  EXPECT_NEAR(fit.add(3.0, 3.5, &innovation), 0.0, 1e-3);  // on the line: no residual
  EXPECT_GE(innovation, 1.0);
}

TEST(ForgettingLineFit, FollowsAChangeOnlyWithForgetting) {
  pe::ForgettingLineFit kept, forgetting;
  for (pe::ForgettingLineFit* fit : {&kept, &forgetting}) fit->reset(Eigen::Vector2d::Zero(), Eigen::Vector2d(10.0, 1.0), 0.01);
  const auto feed = [&](double slope, int from, int to) {
    for (int k = from; k < to; ++k) {
      const double x = 5.0 + 4.0 * std::sin(0.1 * k);
      forgetting.forget(std::exp(-1.0 / 20.0));  // one reading a second, 20 s of memory
      kept.add(x, 1.0 + slope * x);
      forgetting.add(x, 1.0 + slope * x);
    }
  };
  feed(0.5, 0, 400);
  feed(0.8, 400, 600);
  EXPECT_NEAR(forgetting.parameters()(1), 0.8, 1e-3);
  EXPECT_LT(kept.parameters()(1), 0.75);  // without forgetting, the old line still weighs
}

// Noise-free readings and forgetting shrink the covariance each step: its two triangles, rounded
// apart, once drifted until it was no longer positive and the fit diverged (on arm64 first).
TEST(ForgettingLineFit, TheCovarianceStaysSymmetricAndPositive) {
  pe::ForgettingLineFit fit;
  fit.reset(Eigen::Vector2d::Zero(), Eigen::Vector2d(10.0, 1.0), 0.01);
  for (int k = 0; k < 2000; ++k) {
    const double x = 5.0 + 4.0 * std::sin(0.1 * k);
    fit.forget(std::exp(-1.0 / 20.0));
    fit.add(x, 1.0 + (k < 400 ? 0.5 : 0.8) * x);
    const Eigen::Matrix2d& p = fit.covariance();
    ASSERT_EQ(p(0, 1), p(1, 0)) << "reading " << k;
    ASSERT_GT(p(0, 0), 0.0) << "reading " << k;
    ASSERT_GT(p(0, 0) * p(1, 1) - p(0, 1) * p(1, 0), 0.0) << "reading " << k;
  }
  EXPECT_NEAR(fit.parameters()(1), 0.8, 1e-6);
}

TEST(ForgettingLineFit, AStretchWithoutExcitationDoesNotWindTheCovarianceUp) {
  pe::ForgettingLineFit fit;
  fit.reset(Eigen::Vector2d::Zero(), Eigen::Vector2d(2.0, 0.5), 0.1);
  for (int k = 0; k < 100; ++k) fit.add(std::sin(0.3 * k), 1.0);
  for (int k = 0; k < 10000; ++k) {
    fit.forget(0.99);
    fit.add(0.0, 1.0);  // the same x every time: nothing about the slope
  }
  EXPECT_LE(fit.covariance()(1, 1), 0.5 * 0.5 / (0.1 * 0.1) * (1.0 + 1e-12));
  EXPECT_LE(fit.covariance()(0, 0), 2.0 * 2.0 / (0.1 * 0.1) * (1.0 + 1e-12));
  EXPECT_GT(fit.covariance()(1, 1), 0.0);
}

// With the slope held, a reading moves the offset alone and the slope's variance stays; aged by the
// offset only, the slope's variance stays too.
TEST(ForgettingLineFit, AReadingWithTheSlopeHeldMovesTheOffsetAlone) {
  pe::ForgettingLineFit fit;
  fit.reset(Eigen::Vector2d::Zero(), Eigen::Vector2d(2.0, 0.5), 0.1);
  for (int k = 0; k < 100; ++k) fit.add(std::sin(0.3 * k), 1.0 + 0.4 * std::sin(0.3 * k));
  const Eigen::Vector2d before = fit.parameters();
  const double slope_variance = fit.covariance()(1, 1);
  for (int k = 0; k < 3000; ++k) {
    fit.forget(0.99, 1.0);
    fit.addWithSlopeHeld(3.0, 2.5 + 0.4 * 3.0);  // the offset moved to 2.5 where x never varies
  }
  EXPECT_EQ(fit.parameters()(1), before(1));
  EXPECT_NEAR(fit.parameters()(0), 2.5 + 3.0 * (0.4 - before(1)), 1e-6);  // the reading less the held slope times x
  EXPECT_EQ(fit.covariance()(1, 1), slope_variance);
  EXPECT_EQ(fit.covariance()(0, 1), fit.covariance()(1, 0));
  EXPECT_GT(fit.covariance()(0, 0) * fit.covariance()(1, 1) - fit.covariance()(0, 1) * fit.covariance()(1, 0), 0.0);
}
