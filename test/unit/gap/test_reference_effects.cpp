// An effect the vehicle's healthy flights show alike is no change, and not named.
#include <cmath>

#include <gtest/gtest.h>

#include "propulsion_estimator/gap/reference_effects.h"

namespace gap = propulsion_estimator::gap;
namespace fx = propulsion_estimator::effects;

namespace {

gap::ReferenceEffects warmingMotors() {
  gap::ReferenceEffect warming;
  warming.value = -0.0012;
  warming.ci_half = 0.0003;
  warming.signal_low = 25.0;
  warming.signal_high = 45.0;
  return {{fx::Kind::kMotorTemperature, warming}};
}

}  // namespace

// Motors that warm as they did on the healthy flights: the same law, not a change.
TEST(ReferenceEffects, TheSameLawAsOnTheHealthyFlightsIsNoChange) {
  EXPECT_EQ(gap::notAChange(fx::Kind::kMotorTemperature, -0.0014, 0.0002, 38.0, warmingMotors()),
            "not named: no change from the vehicle's healthy flights (-0.0012 +- 0.0003 there, -0.0014 +- 0.0002 "
            "here): the vehicle's own, not what changed");
}

// A motor cooled worse since: its law moved beyond both intervals.
TEST(ReferenceEffects, ALawThatMovedIsAChange) {
  EXPECT_EQ(gap::notAChange(fx::Kind::kMotorTemperature, -0.0025, 0.0002, 60.0, warmingMotors()), "");
}

// The healthy flights cannot vouch for a law where they never flew: far beyond their range (by
// more than its width) the effect is judged against the bench model alone.
TEST(ReferenceEffects, BeyondTheHealthyFlightsRangeTheyCannotSay) {
  EXPECT_EQ(gap::notAChange(fx::Kind::kMotorTemperature, -0.0012, 0.0002, 70.0, warmingMotors()), "");
  EXPECT_NE(gap::notAChange(fx::Kind::kMotorTemperature, -0.0012, 0.0002, 60.0, warmingMotors()), "");
}

// Without the effect on the healthy flights (or without a reference) nothing is held back.
TEST(ReferenceEffects, WithoutTheEffectThereNothingIsHeldBack) {
  EXPECT_EQ(gap::notAChange(fx::Kind::kThrustLoss, 0.05, 0.01, std::nan(""), warmingMotors()), "");
  EXPECT_EQ(gap::notAChange(fx::Kind::kMotorTemperature, -0.0012, 0.0002, 38.0, {}), "");
}
