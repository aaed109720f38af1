// The three views of thrust on one block: the PWM view through the surfaces, the current view
// through the measured current, the RPM view through the measured rotor speeds, and how each
// effect's correction moves them.
#include <cmath>

#include <vector>

#include <gtest/gtest.h>

#include "propulsion_estimator/gap/thrust_views.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "model_variants.h"
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
    block_.signals.set(pe::effects::Signal::kBatteryCurrent, block_.current_a);
    block_.truth_n = 4.0 * views_.motorThrust(1550.0, 11.5);
    // T = a n^2 at the bench's air: each rotor's speed gives a quarter of the truth.
    pe::RpmThrust rpm_thrust;
    rpm_thrust.n_per_rpm2 = 8e-8;
    rpm_thrust.bench_air_density_kg_m3 = 1.2;
    model_.setRpmThrust(rpm_thrust);
    block_.rpm.fill(std::sqrt(block_.truth_n / 4.0 / rpm_thrust.n_per_rpm2));
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

// The air's law reads each rotor's own load: rotors at different pulse widths lose different
// shares of their thrust in the PWM view; the current view sees the cube root of the density ratio.
TEST_F(ThrustViewsTest, ThinAirActsOnEachRotorAtItsOwnThrustAndOnTheCurrentViewAsItsCubeRoot) {
  fx::ModelEffects air;
  air.setParameter(fx::Kind::kAirDensity, 0.6);
  air.air_reference_density_kg_m3 = model_.metadata().benchAirDensity();
  air.full_thrust_n = model_.fullThrustN();
  gap::Block thin = block_;
  thin.signals.set(fx::Signal::kAirDensity, 0.75 * air.air_reference_density_kg_m3);
  thin.pwm_us = {1300.0, 1450.0, 1600.0, 1750.0};
  double expected = 0.0;
  std::vector<double> factors;
  for (int k = 0; k < 4; ++k) {
    const double rotor = views_.surfaceThrust(thin.pwm_us[k], thin.voltage_v);
    factors.push_back(fx::singleThrustFactor(fx::Kind::kAirDensity, 0.6, air, thin.signals, rotor));
    expected += rotor * factors.back();
  }
  EXPECT_NEAR(views_.pwmView(thin, air), expected, 1e-9 * expected);
  EXPECT_GT(factors[3] - factors[0], 0.01) << "a heavily loaded rotor gains more speed in thin air";
  EXPECT_NEAR(views_.currentView(thin, air) / views_.currentView(thin, fx::ModelEffects()), std::cbrt(0.75), 1e-9);
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

TEST_F(ThrustViewsTest, TheRpmViewReadsTheMeasuredSpeedsAtTheFlightsAir) {
  EXPECT_NEAR(views_.rpmView(block_, fx::ModelEffects()), block_.truth_n, 1e-9 * block_.truth_n);
  gap::Block thin = block_;
  thin.signals.set(pe::effects::Signal::kAirDensity, 1.08);
  EXPECT_NEAR(views_.rpmView(thin, fx::ModelEffects()), 0.9 * block_.truth_n, 1e-9 * block_.truth_n);
  views_.setMotorScale(2, 0.8);
  EXPECT_NEAR(views_.rpmView(block_, fx::ModelEffects()), 3.8 / 4.0 * block_.truth_n, 1e-9 * block_.truth_n);
}

// Between the pulse width and the shaft (ESC end points, supply, a warm motor) the RPM view sees
// nothing, nor air density, which it reads; the air on a spinning rotor it sees as the PWM view.
TEST_F(ThrustViewsTest, TheRpmViewSeesTheAirOnTheRotorAndNothingBeforeTheShaft) {
  fx::ModelEffects offset;
  offset.setParameter(fx::Kind::kEscOffset, 30.0);
  EXPECT_NEAR(views_.rpmView(block_, offset), block_.truth_n, 1e-9 * block_.truth_n);
  fx::ModelEffects supply;
  supply.setParameter(fx::Kind::kSupplyResistance, 0.05);
  EXPECT_NEAR(views_.rpmView(block_, supply), block_.truth_n, 1e-9 * block_.truth_n);
  gap::Block warm = block_;
  warm.signals.set(pe::effects::Signal::kMotorTemperature, 60.0);
  fx::ModelEffects heating;
  heating.setParameter(fx::Kind::kMotorTemperature, -0.002);
  heating.motor_reference_c = 20.0;
  EXPECT_LT(views_.pwmView(warm, heating), 0.95 * block_.truth_n);
  EXPECT_NEAR(views_.rpmView(warm, heating), block_.truth_n, 1e-9 * block_.truth_n);
  fx::ModelEffects loss;
  loss.setParameter(fx::Kind::kThrustLoss, 0.05);
  EXPECT_NEAR(views_.rpmView(block_, loss), 0.95 * block_.truth_n, 1e-9 * block_.truth_n);
}

TEST_F(ThrustViewsTest, NoRpmViewWithoutEverySpeedOrAThrustFromRpmOrWhenLeftOut) {
  gap::Block missing = block_;
  missing.rpm[3] = pe::kNaN;
  EXPECT_TRUE(std::isnan(views_.rpmView(missing, fx::ModelEffects())));
  EXPECT_TRUE(std::isnan(gap::ThrustViews(model_, 4, false).rpmView(block_, fx::ModelEffects())));
  model_.setRpmThrust(std::nullopt);
  EXPECT_FALSE(views_.hasRpmThrust());
  EXPECT_TRUE(std::isnan(views_.rpmView(block_, fx::ModelEffects())));
}

// issue 35: outside the domain the views take the model as the node evaluates it (its `outside`
// policy), so that the diagnosis and the node agree on every such sample; an effect's correction
// is the surfaces' response around that value.
TEST_F(ThrustViewsTest, OutsideTheDomainThePlainViewsAreTheNodes) {
  // A sagged pack (10.0 V, below the bench's 10.5 V) and one motor past the top of the PWM range.
  gap::Block outside = block_;
  outside.voltage_v = 10.0;
  outside.pwm_us[2] = 1950.0;
  double node_n = 0.0, node_a = 0.0, surfaces_n = 0.0;
  for (int k = 0; k < 4; ++k) {
    pe::OperatingPoint point;
    ASSERT_TRUE(model_.evaluate(outside.pwm_us[k], outside.voltage_v, &point));
    EXPECT_FALSE(point.in_domain);
    EXPECT_DOUBLE_EQ(views_.motorThrust(outside.pwm_us[k], outside.voltage_v), point.thrust_n);
    node_n += point.thrust_n;
    node_a += point.current_a;
    surfaces_n += views_.surfaceThrust(outside.pwm_us[k], outside.voltage_v);
  }
  ASSERT_GT(std::abs(surfaces_n / node_n - 1.0), 0.01) << "the test needs a point where clamping matters";
  const fx::ModelEffects plain;
  EXPECT_NEAR(views_.pwmView(outside, plain), node_n, 1e-9 * node_n);
  // At the node's own current the current view finds the node's thrust.
  outside.current_a = node_a;
  EXPECT_NEAR(views_.currentView(outside, plain), node_n, 1e-3 * node_n);
  // A correction still moves the view as the surfaces do (the clamp would leave a PWM offset at
  // the top of the range without effect): an ESC offset of 30 us takes what it takes inside.
  fx::ModelEffects offset;
  offset.setParameter(fx::Kind::kEscOffset, 30.0);
  const double shifted = views_.pwmView(outside, offset);
  double expected = node_n;
  for (int k = 0; k < 4; ++k) {
    expected += views_.surfaceThrust(outside.pwm_us[k] - 30.0, outside.voltage_v) -
                views_.surfaceThrust(outside.pwm_us[k], outside.voltage_v);
  }
  EXPECT_NEAR(shifted, expected, 1e-9 * node_n);
  EXPECT_LT(shifted, 0.95 * node_n);
}

TEST_F(ThrustViewsTest, OutsideTheDomainOfAnExtrapolatingModelTheViewsAreTheSurfaces) {
  const pe::PropulsionModel extrapolating = withOutsidePolicy(model_, pe::OutsideDomain::kExtrapolate);
  const gap::ThrustViews views(extrapolating, 4);
  gap::Block outside = block_;
  outside.voltage_v = 10.0;
  double surfaces_n = 0.0;
  for (int k = 0; k < 4; ++k) surfaces_n += views.surfaceThrust(outside.pwm_us[k], outside.voltage_v);
  EXPECT_DOUBLE_EQ(views.pwmView(outside, fx::ModelEffects{}), surfaces_n);
  EXPECT_DOUBLE_EQ(views.motorThrust(1550.0, 10.0), views.surfaceThrust(1550.0, 10.0));
}

TEST(ThrustViewExponent, EachEffectOnThrustSaysHowTheRpmViewSeesIt) {
  EXPECT_DOUBLE_EQ(gap::rpmViewExponent(fx::Kind::kThrustLoss, 0.05), 1.0);
  EXPECT_DOUBLE_EQ(gap::rpmViewExponent(fx::Kind::kGroundEffect, 0.01), 1.0);
  EXPECT_DOUBLE_EQ(gap::rpmViewExponent(fx::Kind::kClimbInflow, 0.01), 1.0);
  EXPECT_DOUBLE_EQ(gap::rpmViewExponent(fx::Kind::kTranslationalLift, 0.01), 1.0);
  EXPECT_DOUBLE_EQ(gap::rpmViewExponent(fx::Kind::kAirDensity, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(gap::rpmViewExponent(fx::Kind::kMotorTemperature, 0.001), 0.0);
  EXPECT_DOUBLE_EQ(gap::rpmViewExponent(fx::Kind::kEscOffset, 10.0), 0.0);
}

TEST(ThrustViewExponent, EachEffectOnThrustSaysHowTheCurrentViewSeesIt) {
  EXPECT_DOUBLE_EQ(gap::currentViewExponent(fx::Kind::kThrustLoss, 0.05), 1.0);
  EXPECT_DOUBLE_EQ(gap::currentViewExponent(fx::Kind::kAirDensity, 0.5), 0.0) << "a law of its own, tested above";
  EXPECT_DOUBLE_EQ(gap::currentViewExponent(fx::Kind::kMotorTemperature, 0.001), -1.0);
  EXPECT_DOUBLE_EQ(gap::currentViewExponent(fx::Kind::kEscOffset, 10.0), 0.0);
}
