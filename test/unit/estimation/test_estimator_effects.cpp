// The model's effects as the Estimator applies them: each changes the estimate by exactly its
// formula (model/model_effects.h), and a missing or stale signal skips its correction.
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "estimator_fixture.h"
#include "propulsion_estimator/common/config_error.h"

namespace {

namespace fx = pe::effects;

constexpr double kPwm = 1690.0;
constexpr double kVoltage = 11.4;  // what EstimatorFixture::fly() reports
constexpr double kInf = std::numeric_limits<double>::infinity();

fx::ModelEffects only(fx::Kind kind, double value) {
  fx::ModelEffects effects;
  effects.setParameter(kind, value);
  effects.rotor_height_m = 0.05;
  effects.motor_reference_c = 22.0;
  return effects;
}

// The surfaces at (pwm, voltage), thrust and efficiency times `factor`: what motor 1 must show.
void expectMotor(const EstimatorFixture& f, double pwm, double voltage, double factor) {
  pe::OperatingPoint plain;
  ASSERT_TRUE(f.model.evaluate(pwm, voltage, &plain));
  const pe::OperatingPoint& got = f.estimator.output().motors[0].estimate;
  EXPECT_DOUBLE_EQ(got.thrust_n, plain.thrust_n * factor);
  EXPECT_DOUBLE_EQ(got.efficiency_n_per_w, plain.efficiency_n_per_w * factor);
  EXPECT_DOUBLE_EQ(got.current_a, plain.current_a);
  EXPECT_DOUBLE_EQ(got.power_w, plain.power_w);
  EXPECT_DOUBLE_EQ(f.estimator.output().motors[0].pwm_us, kPwm) << "the published pulse width is the autopilot's";
}

bool skipped(const EstimatorFixture& f, fx::Kind kind) {
  return (f.estimator.output().effects_skipped & fx::bit(kind)) != 0;
}

double benchDensity(const EstimatorFixture& f) { return f.model.metadata().benchAirDensity(); }

}  // namespace

TEST(EstimatorEffects, EscOffsetShiftsThePulseWidthTheSurfacesSee) {
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(fx::Kind::kEscOffset, 12.0));
  f.fly(kPwm, 0.1);
  expectMotor(f, kPwm - 12.0, kVoltage, 1.0);
  EXPECT_EQ(f.estimator.output().effects_skipped, 0u);
}

TEST(EstimatorEffects, SupplyResistanceLowersTheVoltageByTheDropOfTheBatteryCurrent) {
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(fx::Kind::kSupplyResistance, 0.05));
  // PX4's MAVROS reports the discharge negative; the magnitude is the current drawn.
  EXPECT_EQ(f.estimator.addBatteryCurrent(f.t, -20.0), pe::Rejection::kNone);
  f.fly(kPwm, 0.1);
  expectMotor(f, kPwm, kVoltage - 0.05 * 20.0, 1.0);
  EXPECT_DOUBLE_EQ(f.estimator.output().totals.voltage_v, kVoltage) << "the published voltage is the sensed one";
  EXPECT_EQ(f.estimator.addBatteryCurrent(f.t, 16.0), pe::Rejection::kNone);
  f.fly(kPwm, 0.02);
  expectMotor(f, kPwm, kVoltage - 0.05 * 16.0, 1.0);
}

// The law itself is tested against a motor's torque balance (test_air_density_law.cpp); here, that
// the node applies it to each rotor at that rotor's own thrust, with the model's full thrust.
TEST(EstimatorEffects, AirDensityScalesEachRotorsThrustByTheLawAtItsOwnThrust) {
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(fx::Kind::kAirDensity, 0.85));
  f.estimator.addInput(pe::input::Scalar::kStaticPressure, f.t, 95000.0);
  f.estimator.addInput(pe::input::Scalar::kAirTemperature, f.t, 30.0);
  f.fly(kPwm, 0.1);
  const double rho = 95000.0 / (pe::kSpecificGasConstantDryAir * (30.0 + pe::kZeroCelsiusInKelvin));
  EXPECT_NEAR(benchDensity(f), 101325.0 / (pe::kSpecificGasConstantDryAir * 295.15), 1e-12) << "the model's 22 deg C";
  EXPECT_DOUBLE_EQ(f.model.effects().full_thrust_n, f.model.fullThrustN());
  pe::OperatingPoint plain;
  ASSERT_TRUE(f.model.evaluate(kPwm, kVoltage, &plain));
  const fx::Signals signals = f.estimator.effectSignals(f.t);
  const double factor = fx::singleThrustFactor(fx::Kind::kAirDensity, 0.85, f.model.effects(), signals, plain.thrust_n);
  EXPECT_LT(factor, 1.0);
  EXPECT_LT(factor, std::pow(rho / benchDensity(f), 0.85)) << "below full thrust the exponent is larger";
  expectMotor(f, kPwm, kVoltage, factor);
  EXPECT_NEAR(signals.value(pe::effects::Signal::kAirDensity), rho, 1e-12);
  // Rotors at four pulse widths: each at its own thrust, the lightest losing the most.
  const std::vector<std::uint16_t> channels = {1300, 1500, 1690, 1850, 1000, 1000, 1000, 1000};
  ASSERT_EQ(f.estimator.addMotorOutputs(f.t, f.t, channels.data(), channels.size()), pe::Rejection::kNone);
  double previous = 0.0;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(f.model.evaluate(channels[i], kVoltage, &plain));
    const double own = fx::singleThrustFactor(fx::Kind::kAirDensity, 0.85, f.model.effects(), signals, plain.thrust_n);
    EXPECT_DOUBLE_EQ(f.estimator.output().motors[i].estimate.thrust_n, plain.thrust_n * own) << "motor " << i + 1;
    EXPECT_GT(own, previous) << "motor " << i + 1;
    previous = own;
  }
}

TEST(EstimatorEffects, GroundEffectGrowsAsTheRangefinderNearsTheGround) {
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(fx::Kind::kGroundEffect, 0.0011));
  const Eigen::Vector3d g(0, 0, pe::kStandardGravity);
  f.estimator.addImu(f.t, Eigen::Quaterniond::Identity(), g);
  f.estimator.addRange(f.t, 0.3, 0.1, 12.0);
  f.fly(kPwm, 0.02);
  expectMotor(f, kPwm, kVoltage, 1.0 + 0.0011 / (0.35 * 0.35));
  // Tilted, the rangefinder sees the ground along a slant: the height is range * cos(tilt).
  const Eigen::Quaterniond tilted(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()));
  f.estimator.addImu(f.t, tilted, tilted.conjugate() * g);
  f.estimator.addRange(f.t, 0.3, 0.1, 12.0);
  f.fly(kPwm, 0.02);
  const double height = 0.3 * std::cos(0.2);
  EXPECT_NEAR(f.estimator.effectSignals(f.t).value(pe::effects::Signal::kHeight), height, 1e-12);
  expectMotor(f, kPwm, kVoltage, 1.0 + 0.0011 / ((height + 0.05) * (height + 0.05)));
  // REP-117: nothing within max_range is out of ground effect; closer than min_range is taken as
  // min_range, the least correction the reading allows.
  f.estimator.addImu(f.t, Eigen::Quaterniond::Identity(), g);
  f.estimator.addRange(f.t, kInf, 0.1, 12.0);
  f.fly(kPwm, 0.02);
  expectMotor(f, kPwm, kVoltage, 1.0);
  EXPECT_FALSE(skipped(f, fx::Kind::kGroundEffect));
  f.estimator.addImu(f.t, Eigen::Quaterniond::Identity(), g);
  f.estimator.addRange(f.t, -kInf, 0.1, 12.0);
  f.fly(kPwm, 0.02);
  expectMotor(f, kPwm, kVoltage, 1.0 + 0.0011 / (0.15 * 0.15));
}

TEST(EstimatorEffects, ThrustLossNeedsNoSignal) {
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(fx::Kind::kThrustLoss, 0.04));
  f.fly(kPwm, 0.1);
  expectMotor(f, kPwm, kVoltage, 0.96);
  EXPECT_NEAR(f.estimator.output().totals.mass_kg, 0.96 * f.modelMassKg(kPwm), 1e-12);
}

TEST(EstimatorEffects, MotorTemperatureScalesThrustLinearlyFromItsReference) {
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(fx::Kind::kMotorTemperature, 0.0012));
  f.estimator.addInput(pe::input::Scalar::kMotorTemperature, f.t, 60.0);
  f.fly(kPwm, 0.1);
  expectMotor(f, kPwm, kVoltage, 1.0 + 0.0012 * (60.0 - 22.0));
}

TEST(EstimatorEffects, ClimbInflowTakesThrustInAClimbAndLeavesADescentAlone) {
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(fx::Kind::kClimbInflow, 0.03));
  f.estimator.addVerticalSpeed(f.t, 0.5);
  f.fly(kPwm, 0.1);
  expectMotor(f, kPwm, kVoltage, 1.0 - 0.03 * 0.5);
  f.estimator.addVerticalSpeed(f.t, -0.8);
  f.fly(kPwm, 0.02);
  expectMotor(f, kPwm, kVoltage, 1.0);
}

TEST(EstimatorEffects, AllEffectsTogetherAreTheProductAtTheCorrectedInputs) {
  fx::ModelEffects effects;
  effects.setParameter(fx::Kind::kEscOffset, -8.0);
  effects.setParameter(fx::Kind::kSupplyResistance, 0.03);
  effects.setParameter(fx::Kind::kAirDensity, 1.0);
  effects.setParameter(fx::Kind::kGroundEffect, 0.002);
  effects.rotor_height_m = 0.1;
  effects.setParameter(fx::Kind::kThrustLoss, 0.05);
  effects.setParameter(fx::Kind::kMotorTemperature, -0.002);
  effects.motor_reference_c = 25.0;
  effects.setParameter(fx::Kind::kClimbInflow, 0.04);
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), effects);
  f.estimator.addBatteryCurrent(f.t, 30.0);
  f.estimator.addInput(pe::input::Scalar::kStaticPressure, f.t, 100000.0);
  f.estimator.addInput(pe::input::Scalar::kAirTemperature, f.t, 10.0);
  f.estimator.addRange(f.t, 1.0, 0.1, 12.0);
  f.estimator.addInput(pe::input::Scalar::kMotorTemperature, f.t, 45.0);
  f.estimator.addVerticalSpeed(f.t, 0.2);
  f.fly(kPwm, 0.1);
  const double rho = 100000.0 / (pe::kSpecificGasConstantDryAir * (10.0 + pe::kZeroCelsiusInKelvin));
  const double factor = (rho / benchDensity(f)) * (1.0 + 0.002 / (1.1 * 1.1)) * 0.95 *
                        (1.0 - 0.002 * (45.0 - 25.0)) * (1.0 - 0.04 * 0.2);
  pe::OperatingPoint plain;
  ASSERT_TRUE(f.model.evaluate(kPwm + 8.0, kVoltage - 0.03 * 30.0, &plain));
  EXPECT_NEAR(f.estimator.output().motors[0].estimate.thrust_n, plain.thrust_n * factor, 1e-12);
  EXPECT_EQ(f.estimator.output().effects_skipped, 0u);
  const pe::EstimatorCounters& c = f.estimator.counters();
  for (fx::Kind kind : fx::kAllKinds) {
    if (!effects.has(kind)) continue;
    EXPECT_EQ(c.effect_applied[static_cast<int>(kind)], 5u) << fx::kindName(kind);
    EXPECT_EQ(c.effect_skipped[static_cast<int>(kind)], 0u) << fx::kindName(kind);
  }
}

TEST(EstimatorEffects, WithoutItsSignalACorrectionIsSkippedAndTheOthersApply) {
  fx::ModelEffects effects;
  effects.setParameter(fx::Kind::kSupplyResistance, 0.05);
  effects.setParameter(fx::Kind::kAirDensity, 1.0);
  effects.setParameter(fx::Kind::kGroundEffect, 0.0011);
  effects.rotor_height_m = 0.05;
  effects.setParameter(fx::Kind::kMotorTemperature, 0.001);
  effects.motor_reference_c = 22.0;
  effects.setParameter(fx::Kind::kClimbInflow, 0.03);
  effects.setParameter(fx::Kind::kThrustLoss, 0.04);
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), effects);
  f.fly(kPwm, 0.1);
  expectMotor(f, kPwm, kVoltage, 0.96);
  for (fx::Kind kind : {fx::Kind::kSupplyResistance, fx::Kind::kAirDensity, fx::Kind::kGroundEffect,
                        fx::Kind::kMotorTemperature, fx::Kind::kClimbInflow}) {
    EXPECT_TRUE(skipped(f, kind)) << fx::kindName(kind);
    EXPECT_EQ(f.estimator.counters().effect_skipped[static_cast<int>(kind)], 5u) << fx::kindName(kind);
    EXPECT_EQ(f.estimator.counters().effect_applied[static_cast<int>(kind)], 0u) << fx::kindName(kind);
  }
  EXPECT_FALSE(skipped(f, fx::Kind::kThrustLoss));
  EXPECT_EQ(f.estimator.counters().effect_applied[static_cast<int>(fx::Kind::kThrustLoss)], 5u);
  EXPECT_EQ(f.estimator.counters().effect_skipped[static_cast<int>(fx::Kind::kEscOffset)], 0u) << "not in the model";
}

TEST(EstimatorEffects, AnEffectAtItsNeutralValueIsStillSkippedWithoutItsSignal) {
  // The neutral exponent gives 1 for any density, but a missing density must show as skipped.
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(fx::Kind::kAirDensity, 0.0));
  f.fly(kPwm, 0.1);
  EXPECT_TRUE(skipped(f, fx::Kind::kAirDensity));
  f.estimator.addInput(pe::input::Scalar::kStaticPressure, f.t, 97000.0);
  f.estimator.addInput(pe::input::Scalar::kAirTemperature, f.t, 25.0);
  f.fly(kPwm, 0.02);
  EXPECT_FALSE(skipped(f, fx::Kind::kAirDensity));
  expectMotor(f, kPwm, kVoltage, 1.0);
}

TEST(EstimatorEffects, AStaleSignalSkipsItsCorrectionAfterItsTimeout) {
  const pe::EstimatorConfig config;
  struct Case {
    fx::Kind kind;
    double value;
    double timeout_s;
    std::function<void(pe::Estimator&, double)> feed;
  };
  const Case cases[] = {
      {fx::Kind::kSupplyResistance, 0.05, config.battery_timeout_s,
       [](pe::Estimator& e, double t) { e.addBatteryCurrent(t, -18.0); }},
      {fx::Kind::kAirDensity, 1.0, config.input_timeout_s[pe::input::index(pe::input::Scalar::kStaticPressure)],  // the shorter of the two
       [](pe::Estimator& e, double t) {
         e.addInput(pe::input::Scalar::kStaticPressure, t, 97000.0);
         e.addInput(pe::input::Scalar::kAirTemperature, t, 25.0);
       }},
      {fx::Kind::kGroundEffect, 0.0011, config.input_timeout_s[pe::input::index(pe::input::Scalar::kRangefinder)],
       [](pe::Estimator& e, double t) { e.addRange(t, 0.4, 0.1, 12.0); }},
      {fx::Kind::kMotorTemperature, 0.001, config.input_timeout_s[pe::input::index(pe::input::Scalar::kMotorTemperature)],
       [](pe::Estimator& e, double t) { e.addInput(pe::input::Scalar::kMotorTemperature, t, 50.0); }},
      {fx::Kind::kClimbInflow, 0.03, config.velocity_timeout_s,
       [](pe::Estimator& e, double t) { e.addVerticalSpeed(t, 0.3); }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(fx::kindName(c.kind));
    EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(c.kind, c.value));
    f.fly(kPwm, 0.1);
    expectMotor(f, kPwm, kVoltage, 1.0);
    EXPECT_TRUE(skipped(f, c.kind));
    const double start = f.t;
    c.feed(f.estimator, start);
    f.fly(kPwm, c.timeout_s - 0.05);
    EXPECT_FALSE(skipped(f, c.kind));
    pe::OperatingPoint plain;
    ASSERT_TRUE(f.model.evaluate(kPwm, kVoltage, &plain));
    EXPECT_NE(f.estimator.output().motors[0].estimate.thrust_n, plain.thrust_n);
    f.fly(kPwm, 0.1);
    EXPECT_TRUE(skipped(f, c.kind));
    expectMotor(f, kPwm, kVoltage, 1.0);
    EXPECT_TRUE(std::isnan(f.estimator.effectSignals(f.t).value(fx::requiredSignal(c.kind))));
  }
}

TEST(EstimatorEffects, AirDensityNeedsBothPressureAndTemperatureFresh) {
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(fx::Kind::kAirDensity, 1.0));
  f.estimator.addInput(pe::input::Scalar::kAirTemperature, f.t, 25.0);  // stays fresh 5 s
  for (int k = 0; k < 100; ++k) {  // 2 s of pressure at 50 Hz
    f.estimator.addInput(pe::input::Scalar::kStaticPressure, f.t, 97000.0);
    f.fly(kPwm, 0.02);
  }
  EXPECT_FALSE(skipped(f, fx::Kind::kAirDensity));
  f.fly(kPwm, 1.1);  // the pressure ages out first
  EXPECT_TRUE(skipped(f, fx::Kind::kAirDensity));
  for (int k = 0; k < 150; ++k) {  // then the temperature, with pressure coming again
    f.estimator.addInput(pe::input::Scalar::kStaticPressure, f.t, 97000.0);
    f.fly(kPwm, 0.02);
  }
  EXPECT_TRUE(skipped(f, fx::Kind::kAirDensity));
  EXPECT_TRUE(std::isnan(f.estimator.effectSignals(f.t).value(pe::effects::Signal::kAirDensity)));
}

TEST(EstimatorEffects, NaNBatteryCurrentIsNotMeasuredNotRefused) {
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(fx::Kind::kSupplyResistance, 0.05));
  EXPECT_EQ(f.estimator.addBatteryCurrent(f.t, std::nan("")), pe::Rejection::kNone);
  f.fly(kPwm, 0.1);
  EXPECT_TRUE(skipped(f, fx::Kind::kSupplyResistance));
  EXPECT_EQ(f.estimator.counters().rejected[static_cast<int>(pe::Rejection::kBadBatteryCurrent)], 0u);
}

TEST(EstimatorEffects, RefusesSignalsThatCannotBeTheirQuantity) {
  EstimatorFixture f;
  auto check = [&f](pe::Rejection got, pe::Rejection expected, const char* message) {
    EXPECT_EQ(got, expected) << message;
    EXPECT_EQ(pe::describe(f.estimator.lastRejection()), message);
  };
  check(f.estimator.addBatteryCurrent(f.t, 2.0e4), pe::Rejection::kBadBatteryCurrent,
        "battery current 20000 A refused (must be finite, at most 1000 A either way)");
  check(f.estimator.addBatteryCurrent(f.t, -kInf), pe::Rejection::kBadBatteryCurrent,
        "battery current -inf A refused (must be finite, at most 1000 A either way)");
  check(f.estimator.addInput(pe::input::Scalar::kStaticPressure, f.t, 1013.25), pe::Rejection::kBadInput,
        "static pressure 1013.25 Pa refused (outside 30000..110000 Pa)");
  check(f.estimator.addInput(pe::input::Scalar::kStaticPressure, f.t, std::nan("")), pe::Rejection::kBadInput,
        "static pressure nan Pa refused (outside 30000..110000 Pa)");
  check(f.estimator.addInput(pe::input::Scalar::kAirTemperature, f.t, 293.15), pe::Rejection::kBadInput,
        "air temperature 293.15 deg C refused (outside -60..85 deg C)");
  check(f.estimator.addInput(pe::input::Scalar::kMotorTemperature, f.t, 350.0), pe::Rejection::kBadInput,
        "motor temperature 350 deg C refused (outside -40..200 deg C)");
  check(f.estimator.addRange(f.t, std::nan(""), 0.1, 12.0), pe::Rejection::kBadInput,
        "rangefinder range nan m refused (NaN, or outside the sensor's min_range..max_range 0.1..12 m, which "
        "sensor_msgs/Range says to discard)");
  check(f.estimator.addRange(f.t, 14.0, 0.1, 12.0), pe::Rejection::kBadInput,
        "rangefinder range 14 m refused (NaN, or outside the sensor's min_range..max_range 0.1..12 m, which "
        "sensor_msgs/Range says to discard)");
  check(f.estimator.addRange(f.t, 2.0, 0.0, 0.0), pe::Rejection::kBadInput,
        "rangefinder range 2 m refused (NaN, or outside the sensor's min_range..max_range 0..0 m, which "
        "sensor_msgs/Range says to discard)");
  // Refused readings are not used.
  const fx::Signals signals = f.estimator.effectSignals(f.t);
  EXPECT_TRUE(std::isnan(signals.value(fx::Signal::kBatteryCurrent)));
  EXPECT_TRUE(std::isnan(signals.value(fx::Signal::kAirDensity)));
  EXPECT_TRUE(std::isnan(signals.value(fx::Signal::kHeight)));
  EXPECT_TRUE(std::isnan(signals.value(fx::Signal::kMotorTemperature)));
  EXPECT_STREQ(pe::rejectionName(pe::Rejection::kBadInput), "bad_input");
  EXPECT_EQ(pe::badInputName(pe::input::Scalar::kRangefinder), "bad_rangefinder");
  EXPECT_EQ(pe::badInputName(pe::input::Scalar::kMotorTemperature), "bad_motor_temperature");
  // Each refusal is counted against its input.
  const pe::EstimatorCounters& counters = f.estimator.counters();
  EXPECT_EQ(counters.rejected[static_cast<int>(pe::Rejection::kBadInput)], 7u);
  EXPECT_EQ(counters.rejected_inputs[pe::input::index(pe::input::Scalar::kStaticPressure)], 2u);
  EXPECT_EQ(counters.rejected_inputs[pe::input::index(pe::input::Scalar::kRangefinder)], 3u);
  EXPECT_EQ(counters.rejected_inputs[pe::input::index(pe::input::Scalar::kMotorTemperature)], 1u);
}

TEST(EstimatorEffects, SignalsOfAnotherTimelineAreForgottenWhenTheClockJumpsBack) {
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), only(fx::Kind::kThrustLoss, 0.04));
  f.estimator.addInput(pe::input::Scalar::kMotorTemperature, f.t, 50.0);
  EXPECT_EQ(f.estimator.effectSignals(f.t).value(pe::effects::Signal::kMotorTemperature), 50.0);
  f.t -= 60.0;  // a bag played again
  f.estimator.addBattery(f.t, kVoltage);
  EXPECT_TRUE(std::isnan(f.estimator.effectSignals(f.t).value(pe::effects::Signal::kMotorTemperature)));
}

TEST(EstimatorConfig, RefusesANonPositiveSignalTimeout) {
  pe::EstimatorConfig config;
  config.input_timeout_s[pe::input::index(pe::input::Scalar::kRangefinder)] = 0.0;
  try {
    config.validate(4);
    FAIL() << "accepted";
  } catch (const pe::ConfigError& e) {
    EXPECT_STREQ(e.what(), "rangefinder/timeout_s: must be a positive number, got 0");
  }
}
