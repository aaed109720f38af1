// The air_density correction against a DC motor driving a propeller, solved here by bisection on
// its torque balance: thrust at fixed duty and voltage in thinner or denser air, at every load.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "propulsion_estimator/model/model_effects.h"

namespace fx = propulsion_estimator::effects;

namespace {

// A 920 kV motor with 0.23 ohm of winding and ESC and 0.8 A no-load current on a 9.4-inch
// propeller, at 15 V: the E300's order of magnitude.
struct Motor {
  double torque_constant = 60.0 / (2.0 * M_PI * 920.0);  // N m / A
  double resistance_ohm = 0.23;
  double no_load_current_a = 0.8;
  double torque_per_w2 = 1.6e-7;  // propeller torque over rad/s squared at the bench's air, N m s^2
  double thrust_per_w2 = 1.2e-5;  // N s^2
  double voltage_v = 15.0;

  // Thrust at `duty` in air `ratio` times the bench's density: the speed where the motor's torque
  // meets the propeller's, by bisection.
  double thrustN(double duty, double ratio) const {
    auto excess = [&](double w) {
      const double current = (duty * voltage_v - torque_constant * w) / resistance_ohm;
      return torque_constant * (current - no_load_current_a) - ratio * torque_per_w2 * w * w;
    };
    double low = 0.0, high = duty * voltage_v / torque_constant;
    for (int i = 0; i < 200; ++i) {
      const double middle = 0.5 * (low + high);
      (excess(middle) > 0.0 ? low : high) = middle;
    }
    const double w = 0.5 * (low + high);
    return ratio * thrust_per_w2 * w * w;
  }
  // The law's parameter: the local exponent d ln T / d ln rho at full duty, by central difference.
  double fullThrustExponent() const {
    const double h = 1e-4;
    return (std::log(thrustN(1.0, 1.0 + h)) - std::log(thrustN(1.0, 1.0 - h))) / (std::log(1.0 + h) - std::log(1.0 - h));
  }
};

fx::ModelEffects references(double full_thrust_n) {
  fx::ModelEffects effects;
  effects.air_reference_density_kg_m3 = 1.2;
  effects.full_thrust_n = full_thrust_n;
  return effects;
}

double lawFactor(double parameter, const fx::ModelEffects& references, double ratio, double thrust_n) {
  fx::Signals signals;
  signals.set(fx::Signal::kAirDensity, ratio * references.air_reference_density_kg_m3);
  return fx::singleThrustFactor(fx::Kind::kAirDensity, parameter, references, signals, thrust_n);
}

}  // namespace

TEST(AirDensityLaw, FollowsAMotorsTorqueBalanceAtEveryLoadAndDensity) {
  const Motor motor;
  const double exponent = motor.fullThrustExponent();
  ASSERT_GT(exponent, 0.5);
  ASSERT_LT(exponent, 0.9);
  const fx::ModelEffects refs = references(motor.thrustN(1.0, 1.0));
  for (double duty : {0.25, 0.4, 0.55, 0.7, 0.85, 1.0}) {
    for (double ratio : {0.62, 0.75, 0.9, 1.05, 1.2}) {
      SCOPED_TRACE(testing::Message() << "duty " << duty << ", density ratio " << ratio);
      const double bench = motor.thrustN(duty, 1.0);
      EXPECT_NEAR(lawFactor(exponent, refs, ratio, bench), motor.thrustN(duty, ratio) / bench, 1e-6);
    }
  }
}

TEST(AirDensityLaw, ThinAirCostsALightlyLoadedRotorMoreThanAHeavilyLoadedOne) {
  const Motor motor;
  const fx::ModelEffects refs = references(motor.thrustN(1.0, 1.0));
  const double low = lawFactor(0.7, refs, 0.7, 0.2 * refs.full_thrust_n);
  const double high = lawFactor(0.7, refs, 0.7, refs.full_thrust_n);
  EXPECT_LT(low, high);
  // At full thrust the law's local exponent is its parameter.
  const double h = 1e-4;
  const double local = (std::log(lawFactor(0.7, refs, 1.0 + h, refs.full_thrust_n)) -
                        std::log(lawFactor(0.7, refs, 1.0 - h, refs.full_thrust_n))) /
                       (std::log(1.0 + h) - std::log(1.0 - h));
  EXPECT_NEAR(local, 0.7, 1e-6);
}

TEST(AirDensityLaw, AStiffMotorScalesWithTheDensityAndTheNeutralValueChangesNothing) {
  const fx::ModelEffects refs = references(8.0);
  for (double thrust : {0.0, 2.0, 8.0, 12.0}) {
    EXPECT_NEAR(lawFactor(1.0, refs, 0.8, thrust), 0.8, 1e-12) << thrust << " N";
    EXPECT_DOUBLE_EQ(lawFactor(0.0, refs, 0.8, thrust), 1.0) << thrust << " N";
  }
}

TEST(AirDensityLaw, ATinyParameterIsAlmostNeutralAndAnUnsetFullThrustIsLoud) {
  const fx::ModelEffects refs = references(8.0);
  for (double tiny : {1e-12, 1e-200, 1e-310}) {
    EXPECT_NEAR(lawFactor(tiny, refs, 0.7, 4.0), 1.0, 1e-3) << tiny;
    EXPECT_NEAR(lawFactor(tiny, refs, 0.7, 0.0), 0.7, 1e-12) << tiny << ": at zero thrust the speed holds";
  }
  EXPECT_THROW(lawFactor(0.7, references(std::nan("")), 0.7, 4.0), std::logic_error);
}
