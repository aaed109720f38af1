// Every effect of the registry (effect_list.h) described whole and consistently: what a new
// effect's file must fill in, checked for all of them at once.
#include <cmath>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "propulsion_estimator/model/effect_description.h"

namespace fx = propulsion_estimator::effects;

namespace {

constexpr double kRotorThrustN = 5.0;  // half the references' full thrust

// Signals at which every correction has something to read.
fx::Signals everySignal() {
  fx::Signals signals;
  signals.set(fx::Signal::kBatteryCurrent, 20.0);
  signals.set(fx::Signal::kAirDensity, 1.1);
  signals.set(fx::Signal::kHeight, 0.3);
  signals.set(fx::Signal::kMotorTemperature, 50.0);
  signals.set(fx::Signal::kVerticalSpeed, 1.0);
  signals.set(fx::Signal::kHorizontalSpeed, 3.0);
  signals.set(fx::Signal::kAxialSpeed, 1.0);
  return signals;
}

fx::ModelEffects references() {
  fx::ModelEffects effects;
  effects.air_reference_density_kg_m3 = 1.2;
  effects.full_thrust_n = 10.0;
  effects.rotor_height_m = 0.05;
  effects.motor_reference_c = 22.0;
  return effects;
}

}  // namespace

TEST(EffectDescriptions, NamesAreUniqueAndFoundAgain) {
  std::set<std::string> names;
  for (fx::Kind kind : fx::kAllKinds) {
    const std::string name = fx::kindName(kind);
    EXPECT_TRUE(names.insert(name).second) << name << " twice";
    EXPECT_EQ(fx::kindFromName(name), kind);
  }
  EXPECT_EQ(fx::allNames().size(), fx::kAllKinds.size());
  EXPECT_FALSE(fx::kindFromName("wind").has_value());
}

TEST(EffectDescriptions, EachIsCompleteAndActsOnceEitherOnInputsOrOnThrust) {
  for (fx::Kind kind : fx::kAllKinds) {
    const fx::EffectDescription& d = fx::describe(kind);
    SCOPED_TRACE(d.name);
    EXPECT_NE(std::string(d.parameter.key), "");
    EXPECT_LT(d.parameter.min, d.parameter.max);
    EXPECT_GE(d.parameter.neutral, d.parameter.min);
    EXPECT_LE(d.parameter.neutral, d.parameter.max);
    EXPECT_GT(std::string(d.meaning).size(), 20u);
    EXPECT_NE(d.correct_inputs == nullptr, d.thrust_factor == nullptr) << "one correction of the PWM view";
    EXPECT_TRUE(!d.thrust_factor || d.current_view_exponent || d.current_view_factor)
        << "a thrust factor needs its current view";
    EXPECT_FALSE(d.current_view_exponent && d.current_view_factor) << "one current view";
    EXPECT_TRUE(!d.thrust_factor || d.rpm_view_exponent) << "a thrust factor needs its RPM view";
    EXPECT_EQ(d.informative == nullptr, d.uninformative == nullptr);
    EXPECT_TRUE(!d.reference.key || d.reference.member) << "a reference key needs its place";
    EXPECT_TRUE(!d.informative || d.signal != fx::Signal::kNone) << "informative blocks need a signal";
  }
}

TEST(EffectDescriptions, TheNeutralParameterChangesNothing) {
  const fx::Signals signals = everySignal();
  for (fx::Kind kind : fx::kAllKinds) {
    const fx::EffectDescription& d = fx::describe(kind);
    SCOPED_TRACE(d.name);
    fx::ModelEffects effects = references();
    effects.setParameter(kind, d.parameter.neutral);
    EXPECT_DOUBLE_EQ(fx::thrustFactor(effects, signals, kRotorThrustN), 1.0);
    const fx::Inputs inputs = fx::correctInputs(effects, 1500.0, 11.1, signals);
    EXPECT_DOUBLE_EQ(inputs.pwm_us, 1500.0);
    EXPECT_DOUBLE_EQ(inputs.voltage_v, 11.1);
  }
}

TEST(EffectDescriptions, AParameterInsideItsRangeCorrectsAndItsMissingSignalIsSkipped) {
  for (fx::Kind kind : fx::kAllKinds) {
    const fx::EffectDescription& d = fx::describe(kind);
    SCOPED_TRACE(d.name);
    fx::ModelEffects effects = references();
    effects.setParameter(kind, d.parameter.neutral + 0.25 * (d.parameter.max - d.parameter.neutral));
    EXPECT_NO_THROW(effects.validate());
    const fx::Signals signals = everySignal();
    const fx::Inputs inputs = fx::correctInputs(effects, 1500.0, 11.1, signals);
    const double factor = fx::thrustFactor(effects, signals, kRotorThrustN);
    EXPECT_TRUE(factor != 1.0 || inputs.pwm_us != 1500.0 || inputs.voltage_v != 11.1) << "corrects nothing";
    if (d.signal == fx::Signal::kNone) continue;
    fx::KindMask skipped = 0;
    fx::correctInputs(effects, 1500.0, 11.1, fx::Signals(), &skipped);
    EXPECT_DOUBLE_EQ(fx::thrustFactor(effects, fx::Signals(), kRotorThrustN, &skipped), 1.0);
    EXPECT_EQ(skipped, fx::bit(kind));
  }
}

TEST(EffectDescriptions, OutsideItsRangeIsRefusedNamingTheKey) {
  for (fx::Kind kind : fx::kAllKinds) {
    const fx::EffectDescription& d = fx::describe(kind);
    fx::ModelEffects effects = references();
    effects.setParameter(kind, d.parameter.max + 1.0);
    try {
      effects.validate();
      ADD_FAILURE() << d.name << ": accepted";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("effects.") + d.name + "." + d.parameter.key),
                std::string::npos)
          << e.what();
    }
  }
}
