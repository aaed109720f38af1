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
  EXPECT_EQ(gap::notAChange(fx::Kind::kMotorTemperature, -0.0013, 0.0002, 38.0, warmingMotors()),
            "not named: no change from the vehicle's healthy flights (-0.0012 +- 0.0003 there, -0.0013 +- 0.0002 "
            "here): the vehicle's own, not what changed");
}

// Healthy flights that pin the law loosely: these flights alone would call it a change, the two
// intervals together do not. Not named, and the verdict says why, not that it is the vehicle's own.
TEST(ReferenceEffects, HealthyFlightsThatPinItLooselyCannotVouchForIt) {
  gap::ReferenceEffects loose = warmingMotors();
  loose.at(fx::Kind::kMotorTemperature).ci_half = 0.0009;
  EXPECT_EQ(gap::notAChange(fx::Kind::kMotorTemperature, -0.0018, 0.0002, 38.0, loose),
            "not named: not shown to be a change from the vehicle's healthy flights (-0.0012 +- 0.0009 there, "
            "-0.0018 +- 0.0002 here): these flights alone would call it one, but the healthy flights pin it too "
            "loosely; more of them, or more of its signal on them, would decide");
  EXPECT_EQ(gap::notAChange(fx::Kind::kMotorTemperature, -0.0025, 0.0002, 38.0, loose), "");
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

// With a reference, an effect whose signal the vehicle's state sets (the motors' temperature, the
// height, the speeds) and that changes within flights is judged by its change from the healthy
// flights alone: their fit holds what the vehicle's own parts imitate of it. On the family's
// development seeds (2026-12-03) this named 5 more of 12 motor heatings and nothing wrongly.
TEST(ReferenceEffects, AnEffectReadWithinFlightsIsJudgedByItsChangeFromTheReference) {
  const gap::ReferenceEffects reference = warmingMotors();
  EXPECT_TRUE(gap::judgedByReferenceAlone(fx::Kind::kMotorTemperature, reference, 0.2));
  // Without the signal's split between flights known (NaN), within flights is assumed.
  EXPECT_TRUE(gap::judgedByReferenceAlone(fx::Kind::kMotorTemperature, reference, std::nan("")));
  // Without a reference of the effect, the parts' spread stands in for it.
  EXPECT_FALSE(gap::judgedByReferenceAlone(fx::Kind::kMotorTemperature, {}, 0.2));
  EXPECT_FALSE(gap::judgedByReferenceAlone(fx::Kind::kGroundEffect, reference, 0.2));
}

// Not where the reference cannot pin the effect apart from the parts: a signal that changes mostly
// between flights (the day's air, read on three flights), the battery current (it follows the
// thrust, so what the parts imitate of it moves with each flight's payload: on the development
// seeds it named a supply resistance on a null and a centre-of-gravity case), or none (a thrust
// loss and an ESC offset have the parts' own laws).
TEST(ReferenceEffects, ThePartsSpreadStillJudgesWhatTheReferenceCannotPin) {
  gap::ReferenceEffects reference;
  for (fx::Kind kind : {fx::Kind::kMotorTemperature, fx::Kind::kAirDensity, fx::Kind::kSupplyResistance,
                        fx::Kind::kThrustLoss, fx::Kind::kEscOffset}) {
    reference[kind] = gap::ReferenceEffect{};
  }
  EXPECT_FALSE(gap::judgedByReferenceAlone(fx::Kind::kMotorTemperature, reference, 0.8));
  EXPECT_FALSE(gap::judgedByReferenceAlone(fx::Kind::kAirDensity, reference, 0.9));
  EXPECT_FALSE(gap::judgedByReferenceAlone(fx::Kind::kSupplyResistance, reference, 0.1));
  EXPECT_FALSE(gap::judgedByReferenceAlone(fx::Kind::kThrustLoss, reference, std::nan("")));
  EXPECT_FALSE(gap::judgedByReferenceAlone(fx::Kind::kEscOffset, reference, std::nan("")));
}
