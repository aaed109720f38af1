#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "estimator_fixture.h"
#include "propulsion_estimator/core/config_error.h"
#include "propulsion_estimator/core/payload_estimator.h"

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

TEST(Estimator, HoverMassIsTheSumOfModelThrusts) {
  EstimatorFixture f;
  f.fly(1690.0, 5.0);
  const pe::EstimatorOutput& out = f.estimator.output();
  EXPECT_TRUE(out.hover.hovering);
  const double expected = f.modelMassKg(1690.0);  // thesis eq. 2.1
  EXPECT_NEAR(out.totals.mass_kg, expected, 1e-9);
  EXPECT_NEAR(out.totals.thrust_n, expected * pe::kStandardGravity, 1e-9);
  EXPECT_NEAR(out.payload.total_mass_kg, expected, 1e-9);
  EXPECT_NEAR(out.payload.mass_std_kg, 0.0, 1e-9);
  EXPECT_GT(expected, 1.3);
  EXPECT_LT(expected, 1.45);
  // Symmetric thrust on a symmetric quad: the centre of thrust is the geometric centre.
  EXPECT_NEAR(out.totals.thrust_centre_x_m, 0.0, 1e-12);
  EXPECT_NEAR(out.totals.thrust_centre_y_m, 0.0, 1e-12);
  EXPECT_EQ(out.payload.state, pe::PayloadState::kNoTareYet);
  EXPECT_TRUE(std::isnan(out.payload.payload_mass_kg));
}

TEST(Estimator, PayloadIsTotalMinusTaredEmptyMass) {
  EstimatorFixture f;
  f.fly(1680.0, 4.0);
  const pe::TareResult tare = f.estimator.tare();  // thesis eq. 2.1: W_Q
  ASSERT_TRUE(tare.ok) << tare.message;
  EXPECT_NEAR(tare.empty_mass_kg, f.modelMassKg(1680.0), 1e-9);
  // Land (disarmed), attach the payload, hover higher: eq. 2.2 and 2.3.
  const std::vector<std::uint16_t> disarmed(8, 900);
  EXPECT_EQ(f.estimator.addMotorOutputs(f.t, f.t, disarmed.data(), 8), pe::Rejection::kDisarmed);
  f.t += 1.0;
  f.fly(1760.0, 4.0);
  const pe::MassEstimate& payload = f.estimator.output().payload;
  EXPECT_EQ(payload.state, pe::PayloadState::kHovering);
  EXPECT_EQ(payload.empty_mass_source, pe::EmptyMassSource::kTare);
  EXPECT_NEAR(payload.payload_mass_kg, f.modelMassKg(1760.0) - f.modelMassKg(1680.0), 1e-9);
  EXPECT_GT(payload.payload_mass_kg, 0.15);
}

TEST(Estimator, TareIsRefusedWhenNotHovering) {
  EstimatorFixture f;
  f.fly(1690.0, 1.0);  // the window is not full yet
  const pe::TareResult tare = f.estimator.tare();
  EXPECT_FALSE(tare.ok);
  EXPECT_EQ(tare.message.rfind("refused: not hovering: window spans 0.98 s of the 1.6 s needed", 0), 0u) << tare.message;
}

TEST(Estimator, UrdfMassIsTheEmptyMassUntilTaredAndAfterReset) {
  pe::Vehicle vehicle = pe::Vehicle::quadX(0.225);
  vehicle.empty_mass = pe::MassProperties{1.315};
  EstimatorFixture f({}, vehicle);
  f.fly(1690.0, 4.0);
  EXPECT_EQ(f.estimator.output().payload.empty_mass_source, pe::EmptyMassSource::kUrdf);
  EXPECT_NEAR(f.estimator.output().payload.payload_mass_kg, f.modelMassKg(1690.0) - 1.315, 1e-9);
  ASSERT_TRUE(f.estimator.tare().ok);
  EXPECT_NEAR(f.estimator.output().payload.payload_mass_kg, 0.0, 1e-9);
  f.estimator.reset();
  EXPECT_EQ(f.estimator.output().payload.empty_mass_source, pe::EmptyMassSource::kUrdf);
  EXPECT_EQ(f.estimator.output().payload.state, pe::PayloadState::kWaitingForHover);
}

TEST(Estimator, ParameterEmptyMassOverridesTheUrdf) {
  pe::Vehicle vehicle = pe::Vehicle::quadX(0.225);
  vehicle.empty_mass = pe::MassProperties{1.315};
  pe::EstimatorConfig config;
  config.empty_mass_kg = 1.2;
  EstimatorFixture f(config, vehicle);
  EXPECT_EQ(f.estimator.output().payload.empty_mass_source, pe::EmptyMassSource::kParameter);
  EXPECT_DOUBLE_EQ(f.estimator.output().payload.empty_mass_kg, 1.2);
}

TEST(Estimator, TiltCompensationProjectsThrustOnTheVertical) {
  EstimatorFixture f;
  f.fly(1690.0, 3.0);
  const double level = f.estimator.output().totals.vertical_thrust_n;
  const double roll = 10.0 * M_PI / 180.0;
  const Eigen::Quaterniond tilted(Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
  // Specific force of a vehicle holding altitude while tilted: g along the world vertical.
  const Eigen::Vector3d force = tilted.conjugate() * Eigen::Vector3d(0, 0, pe::kStandardGravity);
  f.estimator.addImu(f.t, tilted, force);
  f.fly(1690.0, 0.02);
  EXPECT_NEAR(f.estimator.output().totals.vertical_thrust_n, level * std::cos(roll), 1e-9);
  EXPECT_NEAR(f.estimator.output().totals.thrust_n, level, 1e-9);
  EXPECT_NEAR(f.estimator.output().hover.max_tilt_rad, roll, 1e-9);
}

TEST(Estimator, AccelerationCompensationDividesByTheMeasuredSpecificForce) {
  EstimatorFixture f;
  const Eigen::Quaterniond level = Eigen::Quaterniond::Identity();
  // Long steady hover: the accelerometer's 0.2 m/s^2 bias is learned, not taken for acceleration.
  for (int k = 0; k < 3000; ++k) {
    f.estimator.addImu(f.t, level, Eigen::Vector3d(0, 0, pe::kStandardGravity + 0.2));
    f.fly(1690.0, 0.02);
  }
  EXPECT_NEAR(f.estimator.output().totals.mass_kg, f.modelMassKg(1690.0), 0.01 * f.modelMassKg(1690.0));
  // Then a real 1 m/s^2 upward acceleration for 1 s: thrust carries m (g + a).
  for (int k = 0; k < 50; ++k) {
    f.estimator.addImu(f.t, level, Eigen::Vector3d(0, 0, pe::kStandardGravity + 1.2));
    f.fly(1690.0, 0.02);
  }
  // 50 steps of the fast (0.3 s) low-pass minus what the slow (30 s) bias average took of the step.
  const double fast = 1.0 - std::pow(1.0 - 0.02 / 0.32, 50);
  const double slow = 1.0 - std::pow(1.0 - 0.02 / 30.02, 50);
  EXPECT_NEAR(f.estimator.output().totals.mass_kg,
              f.modelMassKg(1690.0) * pe::kStandardGravity / (pe::kStandardGravity + fast - slow), 1e-9);
}

TEST(Estimator, RefusesBadVoltage) {
  EstimatorFixture f;
  f.fly(1690.0, 3.0);
  const std::uint64_t accepted = f.estimator.counters().accepted;
  for (double bad : {kNaN, 0.0, -11.1, std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(f.estimator.addBattery(f.t, bad), pe::Rejection::kBadVoltage);
  }
  EXPECT_EQ(f.estimator.counters().rejected[static_cast<int>(pe::Rejection::kBadVoltage)], 4u);
  EXPECT_EQ(pe::describe(f.estimator.lastRejection()), "battery voltage inf V refused (must be finite and positive)");
  // The estimate goes on with the last valid voltage, which is not stale yet.
  f.fly(1690.0, 0.1);
  EXPECT_DOUBLE_EQ(f.estimator.output().totals.voltage_v, 11.4);
  EXPECT_EQ(f.estimator.counters().accepted, accepted + 5);
}

TEST(Estimator, RefusesMotorOutputsWithoutFreshVoltage) {
  EstimatorFixture f;
  const std::vector<std::uint16_t> hover(4, 1690);
  EXPECT_EQ(f.estimator.addMotorOutputs(1.0, 1.0, hover.data(), 4), pe::Rejection::kNoBattery);
  EXPECT_EQ(pe::describe(f.estimator.lastRejection()), "motor outputs ignored: no valid battery voltage received yet");
  f.estimator.addBattery(1.0, 11.4);
  EXPECT_EQ(f.estimator.addMotorOutputs(6.5, 6.5, hover.data(), 4), pe::Rejection::kStaleBattery);
  EXPECT_EQ(pe::describe(f.estimator.lastRejection()),
            "motor outputs ignored: newest battery voltage is 5.5 s old (limit 5 s)");
  EXPECT_EQ(f.estimator.counters().accepted, 0u);
}

TEST(Estimator, RefusesDisarmedMotors) {
  EstimatorFixture f;
  f.fly(1690.0, 3.0);
  const double stamp = f.estimator.output().stamp_s;
  for (std::uint16_t disarmed : {std::uint16_t{0}, std::uint16_t{900}}) {
    std::vector<std::uint16_t> channels(8, 1690);
    channels[2] = disarmed;
    EXPECT_EQ(f.estimator.addMotorOutputs(f.t, f.t, channels.data(), 8), pe::Rejection::kDisarmed);
    f.t += 0.02;
  }
  EXPECT_EQ(pe::describe(f.estimator.lastRejection()),
            "motor outputs ignored: channel 3 at 900 us, at or below disarmed_pwm_max_us 950 (disarmed or stopped)");
  EXPECT_EQ(f.estimator.output().stamp_s, stamp) << "no estimate from a disarmed message";
  EXPECT_EQ(f.estimator.output().payload.window_samples, 0u) << "landing ends the hover episode";
}

TEST(Estimator, RefusesTooFewChannels) {
  EstimatorFixture f;
  f.fly(1690.0, 1.0);
  const std::vector<std::uint16_t> three(3, 1690);
  EXPECT_EQ(f.estimator.addMotorOutputs(f.t, f.t, three.data(), 3), pe::Rejection::kTooFewChannels);
  EXPECT_EQ(pe::describe(f.estimator.lastRejection()),
            "motor outputs ignored: RCOut has 3 channels, motor channel 4 is configured");
}

TEST(Estimator, RefusesTimestampsGoingBackwards) {
  EstimatorFixture f;
  f.fly(1690.0, 1.0);
  const std::vector<std::uint16_t> hover(4, 1690);
  const double stamp = f.estimator.output().stamp_s;
  EXPECT_EQ(f.estimator.addMotorOutputs(stamp - 0.5, f.t, hover.data(), 4), pe::Rejection::kTimeBackwards);
  EXPECT_EQ(pe::describe(f.estimator.lastRejection()), "motor outputs ignored: stamp went back by 0.5 s");
  EXPECT_EQ(f.estimator.output().stamp_s, stamp);
}

TEST(Estimator, ClockJumpingBackResetsInsteadOfRefusing) {
  EstimatorFixture f;
  f.fly(1690.0, 3.0);
  ASSERT_TRUE(f.estimator.output().hover.hovering);
  f.t -= 50.0;  // the bag was played again
  f.last_battery = -1e9;
  f.fly(1690.0, 0.5);
  EXPECT_EQ(f.estimator.counters().clock_resets, 1u);
  EXPECT_FALSE(f.estimator.output().hover.hovering) << "the windows restarted";
  EXPECT_EQ(f.estimator.counters().rejected[static_cast<int>(pe::Rejection::kTimeBackwards)], 0u);
}

TEST(Estimator, FlagsAndCountsSamplesOutsideTheDomain) {
  EstimatorFixture f;
  f.fly(1100.0, 1.0);  // armed idle below the measured 1200 us: clamped and flagged
  EXPECT_EQ(f.estimator.output().totals.motors_out_of_domain, 4);
  EXPECT_FALSE(f.estimator.output().motors[0].estimate.in_domain);
  EXPECT_EQ(f.estimator.counters().motor_samples_outside_domain, f.estimator.counters().motor_samples);
}

TEST(EstimatorConfig, RefusesChannelsThatDoNotFitTheVehicle) {
  auto refusal = [](pe::EstimatorConfig config) -> std::string {
    try {
      config.validate(4);
    } catch (const pe::ConfigError& e) {
      return e.what();
    }
    return "accepted";
  };
  pe::EstimatorConfig config;
  config.motor_channels = {1, 2, 3, 4, 5, 6};
  EXPECT_EQ(refusal(config), "motor_channels: 6 channels for a vehicle with 4 rotors");
  config.motor_channels = {1, 2, 2, 4};
  EXPECT_EQ(refusal(config), "motor_channels: channel 2 is listed twice");
  config.motor_channels = {0, 1, 2, 3};
  EXPECT_EQ(refusal(config), "motor_channels: channel 0 is outside 1..32 (channels are 1-based)");
  config = pe::EstimatorConfig{};
  config.battery_timeout_s = -1.0;
  EXPECT_EQ(refusal(config), "battery_timeout_s: must be a positive number, got -1");
}
