// The two views of thrust on one block: the PWM view through the surfaces, the current view
// through the measured current, and how each effect's correction moves them.
#include <cmath>

#include <gtest/gtest.h>

#include "propulsion_estimator/gap/thrust_views.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;
namespace gap = propulsion_estimator::gap;
namespace fx = propulsion_estimator::effects;

namespace {

class ThrustViewsTest : public ::testing::Test {
 protected:
  ThrustViewsTest() : model_(pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"))), views_(model_, 4) {
    for (int k = 0; k < 4; ++k) {
      block_.pwm_us[k] = 1550.0;
      block_.axis_up[k] = 1.0;
    }
    block_.voltage_v = 11.5;
    block_.current_a = 4.0 * model_.evaluateRaw(pe::Output::kCurrent, 1550.0, 11.5);
    block_.signals.battery_current_a = block_.current_a;
    block_.truth_n = 4.0 * views_.motorThrust(1550.0, 11.5);
  }

  pe::PropulsionModel model_;
  gap::ThrustViews views_;
  gap::Block block_;
};

}  // namespace

TEST_F(ThrustViewsTest, BothViewsAgreeOnAPlainModelAtItsOwnCurrent) {
  const fx::ModelEffects plain;
  EXPECT_NEAR(views_.pwmView(block_, plain), block_.truth_n, 1e-9);
  EXPECT_NEAR(views_.currentView(block_, plain), block_.truth_n, 1e-3 * block_.truth_n);
}

TEST_F(ThrustViewsTest, AThrustLossMovesBothViewsAlike) {
  fx::ModelEffects loss;
  loss.setParameter(fx::Kind::kThrustLoss, 0.05);
  EXPECT_NEAR(views_.pwmView(block_, loss), 0.95 * block_.truth_n, 1e-9);
  EXPECT_NEAR(views_.currentView(block_, loss), 0.95 * block_.truth_n, 1e-3 * block_.truth_n);
}

TEST_F(ThrustViewsTest, AnEscOffsetLeavesTheCurrentViewAlone) {
  fx::ModelEffects offset;
  offset.setParameter(fx::Kind::kEscOffset, 30.0);
  EXPECT_LT(views_.pwmView(block_, offset), 0.95 * block_.truth_n);
  EXPECT_NEAR(views_.currentView(block_, offset), block_.truth_n, 1e-3 * block_.truth_n);
}

TEST_F(ThrustViewsTest, AMotorScaleActsOnItsMotorAlone) {
  views_.setMotorScale(2, 0.8);
  EXPECT_NEAR(views_.pwmView(block_, fx::ModelEffects()), 3.8 / 4.0 * block_.truth_n, 1e-9);
}

TEST_F(ThrustViewsTest, NoCurrentViewWithoutACurrentOrOutOfReach) {
  gap::Block without = block_;
  without.current_a = pe::kNaN;
  EXPECT_TRUE(std::isnan(views_.currentView(without, fx::ModelEffects())));
  gap::Block huge = block_;
  huge.current_a = 1e4;
  EXPECT_TRUE(std::isnan(views_.currentView(huge, fx::ModelEffects())));
}

TEST(ThrustViewExponent, EachEffectOnThrustSaysHowTheCurrentViewSeesIt) {
  EXPECT_DOUBLE_EQ(gap::currentViewExponent(fx::Kind::kThrustLoss, 0.05), 1.0);
  EXPECT_DOUBLE_EQ(gap::currentViewExponent(fx::Kind::kAirDensity, 0.5), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(gap::currentViewExponent(fx::Kind::kMotorTemperature, 0.001), -1.0);
  EXPECT_DOUBLE_EQ(gap::currentViewExponent(fx::Kind::kEscOffset, 10.0), 0.0);
}
