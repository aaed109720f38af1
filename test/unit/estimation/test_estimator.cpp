#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "estimator_fixture.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/estimation/payload_estimator.h"
#include "propulsion_estimator/common/yaml_map.h"

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
  const pe::TareResult tare = f.estimator.tare(f.t);  // thesis eq. 2.1: W_Q
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
  const pe::TareResult tare = f.estimator.tare(f.t);
  EXPECT_FALSE(tare.ok);
  EXPECT_EQ(tare.message.rfind("refused: not hovering: window spans 0.98 s of the 1.6 s needed", 0), 0u) << tare.message;
}

TEST(Estimator, AHoverVerdictExpiresWhenNoMotorOutputIsAcceptedWithinItsWindow) {
  EstimatorFixture within;
  within.fly(1690.0, 4.0);
  EXPECT_TRUE(within.estimator.tare(within.t + 1.9).ok) << "the last sample is 1.92 s old: within hover/window_s";

  // The battery topic stops, then the vehicle lands and disarms: every message is refused as
  // stale_battery before its disarm could end the hover.
  EstimatorFixture f;
  f.fly(1690.0, 4.0);
  ASSERT_TRUE(f.estimator.output().hover.hovering);
  const double averaged = f.estimator.output().payload.total_mass_kg;
  const std::vector<std::uint16_t> disarmed(8, 900);
  EXPECT_EQ(f.estimator.addMotorOutputs(f.t + 6.0, f.t + 6.0, disarmed.data(), 8), pe::Rejection::kStaleBattery);
  const pe::EstimatorOutput& out = f.estimator.output();
  EXPECT_FALSE(out.hover.hovering);
  EXPECT_EQ(out.hover.blocker, pe::HoverBlocker::kExpired);
  EXPECT_FALSE(out.payload.hovering);
  EXPECT_EQ(out.payload.total_mass_kg, averaged) << "the last hover's average is held";
  EXPECT_EQ(f.estimator.describeHover().rfind(
                "not hovering: no sample within the last hover/window_s 2 s (the last verdict expired); window 0 "
                "samples",
                0),
            0u)
      << f.estimator.describeHover();
  const pe::TareResult tare = f.estimator.tare(f.t + 6.5);
  EXPECT_FALSE(tare.ok);
  EXPECT_EQ(tare.message,
            "refused: no motor outputs accepted for 6.52 s, longer than hover/window_s 2 s: the last hover verdict "
            "expired");
  EXPECT_EQ(out.payload.empty_mass_source, pe::EmptyMassSource::kNone) << "nothing was tared";

  // No input at all after the hover: tare alone sees the verdict expire.
  EstimatorFixture silent;
  silent.fly(1690.0, 4.0);
  const pe::TareResult late = silent.estimator.tare(silent.t + 2.5);
  EXPECT_FALSE(late.ok);
  EXPECT_EQ(late.message,
            "refused: no motor outputs accepted for 2.52 s, longer than hover/window_s 2 s: the last hover verdict "
            "expired");
  // Motor outputs again: the window fills anew.
  silent.t += 2.5;
  silent.fly(1690.0, 3.0);
  EXPECT_TRUE(silent.estimator.output().hover.hovering);
}

TEST(Estimator, UrdfMassIsTheEmptyMassUntilTaredAndAfterReset) {
  pe::Vehicle vehicle = pe::Vehicle::quadX(0.225);
  vehicle.empty_mass = pe::MassProperties{1.315};
  EstimatorFixture f({}, vehicle);
  f.fly(1690.0, 4.0);
  EXPECT_EQ(f.estimator.output().payload.empty_mass_source, pe::EmptyMassSource::kUrdf);
  EXPECT_NEAR(f.estimator.output().payload.payload_mass_kg, f.modelMassKg(1690.0) - 1.315, 1e-9);
  ASSERT_TRUE(f.estimator.tare(f.t).ok);
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
  // The accelerometer reads true on the ground, then a 0.2 m/s^2 bias (warming up) for two
  // minutes of hover: taken as acceleration, the bias alone would be a 2 % mass error.
  f.estimator.addImu(f.t, level, Eigen::Vector3d(0, 0, pe::kStandardGravity));
  for (int k = 0; k < 6000; ++k) {
    f.estimator.addImu(f.t, level, Eigen::Vector3d(0, 0, pe::kStandardGravity + 0.2));
    f.fly(1690.0, 0.02);
  }
  const double learned = 1.0 - std::pow(1.0 - 0.02 / 30.02, 6000);  // share of the bias the slow average took
  EXPECT_GT(learned, 0.98);
  EXPECT_NEAR(f.estimator.output().totals.mass_kg,
              f.modelMassKg(1690.0) * pe::kStandardGravity / (pe::kStandardGravity + 0.2 * (1.0 - learned)), 1e-6);
  // Then a real 1 m/s^2 upward acceleration for 1 s: thrust carries m (g + a).
  const double bias = 0.2 * learned;
  for (int k = 0; k < 50; ++k) {
    f.estimator.addImu(f.t, level, Eigen::Vector3d(0, 0, pe::kStandardGravity + 1.2));
    f.fly(1690.0, 0.02);
  }
  // 50 steps of the fast (0.3 s) low-pass minus what the slow (30 s) bias average took of the step.
  const double fast = 0.2 + 1.0 * (1.0 - std::pow(1.0 - 0.02 / 0.32, 50));
  const double slow = bias + (1.2 - bias) * (1.0 - std::pow(1.0 - 0.02 / 30.02, 50));
  EXPECT_NEAR(f.estimator.output().totals.mass_kg,
              f.modelMassKg(1690.0) * pe::kStandardGravity / (pe::kStandardGravity + fast - slow), 2e-4);
}

TEST(VerticalAccelerationFilter, OneSampleAfterAGapMovesTheBiasByOneCappedStepOnly) {
  pe::VerticalAccelerationFilter filter(0.3, 30.0);
  for (int k = 0; k <= 100; ++k) filter.add(0.02 * k, 0.0);  // at rest, no bias
  // A 10 s gap in the IMU, then a 5 m/s^2 jolt: the fast low-pass follows it (its old value is
  // stale), the bias average takes it as one sample of kMaxBiasStepS, not as 10 s of bias (25 %).
  const double dt = pe::VerticalAccelerationFilter::kMaxBiasStepS;
  EXPECT_EQ(dt, 0.1);
  const double fast = 5.0 * 10.0 / (0.3 + 10.0);
  const double bias = 5.0 * dt / (30.0 + dt);
  EXPECT_NEAR(filter.add(12.0, 5.0), fast - bias, 1e-12);
  // A regular step is not capped: 0.02 s at 50 Hz.
  EXPECT_NEAR(filter.add(12.02, 5.0), fast + (5.0 - fast) * 0.02 / 0.32 - (bias + (5.0 - bias) * 0.02 / 30.02),
              1e-12);
}

TEST(Estimator, StaleImuIsNotUsed) {
  EstimatorFixture f;
  const Eigen::Quaterniond tilted(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()));
  f.estimator.addImu(f.t, tilted, tilted.conjugate() * Eigen::Vector3d(0, 0, pe::kStandardGravity));
  f.fly(1690.0, 0.4);  // within imu/timeout_s 0.5 s: projected
  EXPECT_NEAR(f.estimator.output().totals.vertical_thrust_n, f.estimator.output().totals.thrust_n * std::cos(0.2),
              1e-9);
  f.fly(1690.0, 0.2);  // older: level assumed, and the hover detector sees no tilt
  EXPECT_DOUBLE_EQ(f.estimator.output().totals.vertical_thrust_n, f.estimator.output().totals.thrust_n);
  // The window still holds the tilted samples of the fresh period, none newer.
  EXPECT_NEAR(f.estimator.output().hover.max_tilt_rad, 0.2, 1e-9);
}

TEST(Estimator, RefusesBadImuAndVelocity) {
  EstimatorFixture f;
  f.fly(1690.0, 1.0);
  const Eigen::Vector3d g(0, 0, pe::kStandardGravity);
  EXPECT_EQ(f.estimator.addImu(f.t, Eigen::Quaterniond(0, 0, 0, 0), g), pe::Rejection::kBadImu);
  EXPECT_EQ(f.estimator.addImu(f.t, Eigen::Quaterniond(2, 0, 0, 0), g), pe::Rejection::kBadImu);
  EXPECT_EQ(f.estimator.addImu(f.t, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, kNaN, 9.8)),
            pe::Rejection::kBadImu);
  EXPECT_EQ(pe::describe(f.estimator.lastRejection()),
            "IMU message refused (non-finite or non-unit orientation, or non-finite acceleration)");
  EXPECT_EQ(f.estimator.addVerticalSpeed(f.t, kNaN), pe::Rejection::kBadVelocity);
  EXPECT_EQ(pe::describe(f.estimator.lastRejection()), "vertical speed nan m/s refused (not finite)");
  f.fly(1690.0, 0.1);  // refused inputs are not used: level, no vertical speed
  EXPECT_DOUBLE_EQ(f.estimator.output().totals.vertical_thrust_n, f.estimator.output().totals.thrust_n);
  EXPECT_TRUE(std::isnan(f.estimator.output().hover.max_abs_vertical_speed_m_s));
}

TEST(Estimator, RefusesBadVoltage) {
  EstimatorFixture f;
  f.fly(1690.0, 3.0);
  const std::uint64_t accepted = f.estimator.counters().accepted;
  const std::pair<double, const char*> bad[] = {
      {kNaN, "battery voltage nan V refused (must be finite and positive)"},
      {0.0, "battery voltage 0 V refused (must be finite and positive)"},
      {-11.1, "battery voltage -11.1 V refused (must be finite and positive)"},
      {std::numeric_limits<double>::infinity(), "battery voltage inf V refused (must be finite and positive)"}};
  for (const auto& [voltage, message] : bad) {
    EXPECT_EQ(f.estimator.addBattery(f.t, voltage), pe::Rejection::kBadVoltage);
    EXPECT_EQ(pe::describe(f.estimator.lastRejection()), message);
  }
  EXPECT_EQ(f.estimator.counters().rejected[static_cast<int>(pe::Rejection::kBadVoltage)], 4u);
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
  const std::pair<std::uint16_t, const char*> disarmed[] = {
      {0, "motor outputs ignored: channel 3 at 0 us, at or below disarmed_pwm_max_us 950 (disarmed or stopped)"},
      {900, "motor outputs ignored: channel 3 at 900 us, at or below disarmed_pwm_max_us 950 (disarmed or stopped)"}};
  for (const auto& [pwm, message] : disarmed) {
    std::vector<std::uint16_t> channels(8, 1690);
    channels[2] = pwm;
    EXPECT_EQ(f.estimator.addMotorOutputs(f.t, f.t, channels.data(), 8), pe::Rejection::kDisarmed);
    EXPECT_EQ(pe::describe(f.estimator.lastRejection()), message);
    f.t += 0.02;
  }
  EXPECT_EQ(f.estimator.output().stamp_s, stamp) << "no estimate from a disarmed message";
  EXPECT_EQ(f.estimator.output().motors[2].pwm_us, 1690.0);
  EXPECT_EQ(f.estimator.output().payload.window_samples, 0u) << "landing ends the hover episode";
}

TEST(Estimator, RefusesTooFewChannels) {
  EstimatorFixture f;
  f.fly(1690.0, 1.0);
  const double stamp = f.estimator.output().stamp_s;
  const std::vector<std::uint16_t> three(3, 1750);
  EXPECT_EQ(f.estimator.addMotorOutputs(f.t, f.t, three.data(), 3), pe::Rejection::kTooFewChannels);
  EXPECT_EQ(pe::describe(f.estimator.lastRejection()),
            "motor outputs ignored: RCOut has 3 channels, motor channel 4 is configured");
  EXPECT_EQ(f.estimator.output().stamp_s, stamp);
  EXPECT_EQ(f.estimator.output().motors[0].pwm_us, 1690.0) << "no estimate built on it";
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

TEST(Estimator, RefusesAStampFarAheadWithoutRefusingTheFollowingOnes) {
  EstimatorFixture f;
  f.fly(1690.0, 1.0);
  const std::vector<std::uint16_t> hover(4, 1690);
  const double stamp = f.estimator.output().stamp_s;
  EXPECT_EQ(f.estimator.addMotorOutputs(f.t + 1.0, f.t, hover.data(), 4), pe::Rejection::kStampAhead);
  EXPECT_EQ(pe::describe(f.estimator.lastRejection()),
            "motor outputs ignored: stamped 1 s ahead of the receiving clock (limit max_stamp_ahead_s 0.5 s)");
  EXPECT_EQ(f.estimator.output().stamp_s, stamp);
  f.t += 0.02;
  f.fly(1690.0, 1.0);  // each accepted: the refused stamp is not the last one
  EXPECT_EQ(f.estimator.counters().rejected[static_cast<int>(pe::Rejection::kTimeBackwards)], 0u);
  EXPECT_EQ(f.estimator.counters().rejected[static_cast<int>(pe::Rejection::kStampAhead)], 1u);
  // Within max_stamp_ahead_s (a replayed bag's clock lagging its stamps) a stamp is accepted.
  EXPECT_EQ(f.estimator.addMotorOutputs(f.t + 0.4, f.t, hover.data(), 4), pe::Rejection::kNone);
}

TEST(Estimator, RefusesADuplicateStampOnceAndCountsItNowhereElse) {
  EstimatorFixture f;
  f.fly(1690.0, 3.0);
  const pe::EstimatorOutput& out = f.estimator.output();
  ASSERT_TRUE(out.hover.hovering);
  const std::uint32_t averaged = out.payload.window_samples;
  const std::size_t judged = out.hover.samples;
  const std::uint64_t accepted = f.estimator.counters().accepted;
  const std::vector<std::uint16_t> hover(4, 1690);
  EXPECT_EQ(f.estimator.addMotorOutputs(out.stamp_s, f.t, hover.data(), 4), pe::Rejection::kDuplicate);
  EXPECT_EQ(pe::describe(f.estimator.lastRejection()),
            "motor outputs ignored: stamp 102.98 s is the previous accepted message's (a duplicate)");
  EXPECT_EQ(f.estimator.counters().rejected[static_cast<int>(pe::Rejection::kDuplicate)], 1u);
  EXPECT_EQ(f.estimator.counters().rejected[static_cast<int>(pe::Rejection::kTimeBackwards)], 0u);
  EXPECT_EQ(f.estimator.counters().accepted, accepted);
  EXPECT_EQ(out.payload.window_samples, averaged);
  EXPECT_EQ(out.hover.samples, judged);
  // Unstamped messages are stamped on arrival: two within one tick of a simulated clock are two.
  EXPECT_EQ(f.estimator.addMotorOutputs(0.0, f.t, hover.data(), 4), pe::Rejection::kNone);
  EXPECT_EQ(f.estimator.addMotorOutputs(0.0, f.t, hover.data(), 4), pe::Rejection::kNone);
  EXPECT_EQ(out.payload.window_samples, averaged + 2);
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

TEST(Estimator, StampsThatRestartResetInsteadOfRefusingForever) {
  EstimatorFixture f;
  f.fly(1690.0, 3.0);
  ASSERT_TRUE(f.estimator.output().hover.hovering);
  // The autopilot rebooted: its stamps start again near zero while the receiving clock goes on.
  const std::vector<std::uint16_t> hover(4, 1690);
  for (int k = 0; k < 150; ++k, f.t += 0.02) {
    if (k % 50 == 0) f.estimator.addBattery(f.t, 11.4);
    EXPECT_EQ(f.estimator.addMotorOutputs(1.0 + 0.02 * k, f.t, hover.data(), 4), pe::Rejection::kNone) << k;
  }
  EXPECT_EQ(f.estimator.counters().clock_resets, 1u);
  EXPECT_TRUE(f.estimator.output().hover.hovering) << "the windows filled again on the new stamps";
  EXPECT_EQ(f.estimator.counters().rejected[static_cast<int>(pe::Rejection::kTimeBackwards)], 0u);
}

TEST(Estimator, FlagsAndCountsSamplesOutsideTheDomain) {
  EstimatorFixture f;
  f.fly(1100.0, 1.0);  // armed idle below the measured 1200 us: clamped and flagged
  EXPECT_EQ(f.estimator.output().totals.motors_out_of_domain, 4);
  EXPECT_FALSE(f.estimator.output().motors[0].estimate.in_domain);
  EXPECT_EQ(f.estimator.counters().motor_samples_outside_domain, f.estimator.counters().motor_samples);
}

TEST(Estimator, RejectPolicyRefusesTheWholeMessageBeforeTouchingTheEstimates) {
  std::string text = pe::readTextFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  text.replace(text.find("outside: clamp"), 14, "outside: reject");
  pe::Estimator estimator(pe::parseModelYaml(text, "reject.yaml"), pe::Vehicle::quadX(0.225), {});
  estimator.addBattery(0.0, 11.4);
  const std::vector<std::uint16_t> hover(4, 1690);
  ASSERT_EQ(estimator.addMotorOutputs(0.02, 0.02, hover.data(), 4), pe::Rejection::kNone);
  const std::vector<std::uint16_t> one_outside{1700, 1700, 1950, 1700};
  EXPECT_EQ(estimator.addMotorOutputs(0.04, 0.04, one_outside.data(), 4), pe::Rejection::kOutsideDomain);
  EXPECT_EQ(pe::describe(estimator.lastRejection()),
            "motor outputs ignored: channel 3 at 1950 us (or the voltage) outside the model's domain, which says "
            "reject");
  for (const pe::MotorOutput& motor : estimator.output().motors) EXPECT_EQ(motor.pwm_us, 1690.0);
  double sum = 0.0;
  for (const pe::MotorOutput& motor : estimator.output().motors) sum += motor.estimate.thrust_n;
  EXPECT_DOUBLE_EQ(sum, estimator.output().totals.thrust_n) << "motors and totals still describe one message";
}

TEST(Estimator, RefusesNonFiniteModelOutputs) {
  // Thrust -1000 / (x - 1500): positive and finite over a domain ending at 1400 us, so the loader
  // accepts it; extrapolated to 1500 us it meets its pole.
  std::string text = pe::readTextFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  text.replace(text.find("pwm_us: [1200, 1900]"), 20, "pwm_us: [1200, 1400]");
  text.replace(text.find("outside: clamp"), 14, "outside: extrapolate");
  const std::string thrust = "polynomial: {p00: 2418, p10: -2.912, p01: -139.1, p20: 7.806e-4, p11: 0.1145}";
  text.replace(text.find(thrust), thrust.size(), "numerator: {p00: -1000}\n    denominator: {p00: -1500, p10: 1}");
  pe::Estimator estimator(pe::parseModelYaml(text, "pole.yaml"), pe::Vehicle::quadX(0.225), {});
  estimator.addBattery(0.0, 11.4);
  const std::vector<std::uint16_t> at_pole(4, 1500);
  EXPECT_EQ(estimator.addMotorOutputs(0.02, 0.02, at_pole.data(), 4), pe::Rejection::kNonFiniteEstimate);
  EXPECT_EQ(pe::describe(estimator.lastRejection()),
            "motor outputs ignored: the model gives a non-finite value for channel 1 at 1500 us and 11.4 V (a pole of "
            "a rational surface when extrapolating?)");
  EXPECT_EQ(estimator.counters().accepted, 0u);
}

TEST(Estimator, ModelWithoutCurrentPowerAndEfficiencyEstimatesTheRestAndPublishesNaN) {
  const pe::PropulsionModel model = thrustOnlyThesisModel();
  pe::Estimator estimator(model, pe::Vehicle::quadX(0.225), {});
  const EstimatorFixture thesis;  // the same thrust surface with every output
  estimator.addBattery(0.0, 11.4);
  const std::vector<std::uint16_t> hover(4, 1690);
  for (int k = 1; k <= 150; ++k) {
    ASSERT_EQ(estimator.addMotorOutputs(0.02 * k, 0.02 * k, hover.data(), 4), pe::Rejection::kNone) << k;
  }
  const pe::EstimatorOutput& out = estimator.output();
  for (const pe::MotorOutput& motor : out.motors) {
    EXPECT_NEAR(motor.estimate.thrust_n, thesis.modelMassKg(1690.0) * pe::kStandardGravity / 4.0, 1e-9);
    EXPECT_TRUE(std::isnan(motor.estimate.current_a));
    EXPECT_TRUE(std::isnan(motor.estimate.power_w));
    EXPECT_TRUE(std::isnan(motor.estimate.efficiency_n_per_w));
    EXPECT_GT(motor.estimate.rpm, 0.0);
  }
  EXPECT_TRUE(std::isnan(out.totals.current_a));
  EXPECT_TRUE(std::isnan(out.totals.power_w));
  EXPECT_TRUE(std::isnan(out.totals.efficiency_n_per_w));
  EXPECT_NEAR(out.totals.mass_kg, thesis.modelMassKg(1690.0), 1e-9);
  EXPECT_TRUE(out.hover.hovering);
  EXPECT_NEAR(out.payload.total_mass_kg, thesis.modelMassKg(1690.0), 1e-9);
  EXPECT_EQ(estimator.counters().accepted, 150u);
  EXPECT_EQ(estimator.counters().rejected[static_cast<int>(pe::Rejection::kNonFiniteEstimate)], 0u);
}

namespace {

// What validate() says of `config` for a quad: its refusal, or "accepted".
std::string refusal(const pe::EstimatorConfig& config) {
  try {
    config.validate(4);
  } catch (const pe::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(EstimatorConfig, RefusesChannelsThatDoNotFitTheVehicle) {
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
  config = pe::EstimatorConfig{};
  config.max_stamp_ahead_s = 0.0;
  EXPECT_EQ(refusal(config), "max_stamp_ahead_s: must be a positive number, got 0");
}

TEST(EstimatorConfig, RefusesAWindowFillTheBinsCannotMeet) {
  pe::EstimatorConfig config;
  config.hover.min_window_fill = 0.99;  // the 64 bins guarantee only 63/64 = 0.984 of the window
  EXPECT_EQ(refusal(config),
            "hover/min_window_fill: 0.99 is never reliably met: the window keeps its samples in 64 bins and spans "
            "at least 0.9844 of hover/window_s");
  config.hover.min_window_fill = 63.0 / 64.0;
  EXPECT_EQ(refusal(config), "accepted");
  config = pe::EstimatorConfig{};
  config.payload.averaging_window_s = 1e300;  // the whole episode: fixed memory at any length
  EXPECT_EQ(refusal(config), "accepted");
  EXPECT_EQ(refusal(pe::EstimatorConfig{}), "accepted");
}

TEST(Estimator, DetectsHoverAndTaresAtAnyRate) {
  // The windows were once sized in samples for 100 Hz: above about 126 Hz a full one spanned less
  // than the hover detector needs, and hover was never detected.
  for (const double rate_hz : {10.0, 50.0, 400.0, 1000.0, 2000.0}) {
    EstimatorFixture f;
    f.period_s = 1.0 / rate_hz;
    f.fly(1690.0, 6.0);
    const pe::EstimatorOutput& out = f.estimator.output();
    EXPECT_TRUE(out.hover.hovering) << rate_hz << " Hz: " << f.estimator.describeHover();
    EXPECT_NEAR(out.payload.total_mass_kg, f.modelMassKg(1690.0), 1e-9) << rate_hz << " Hz";
    EXPECT_TRUE(f.estimator.tare(f.t).ok) << rate_hz << " Hz";
  }
}

TEST(Estimator, BarometerGivesTheHoverVerticalSpeedWithoutVelocity) {
  // A steady climb at 1 m/s (the pressure falling by rho g = 11.8 Pa/s) is no hover, though the
  // thrust is steady: the barometer stands in for the missing velocity topic.
  const auto climb = [](double rate_m_s) {
    EstimatorFixture f;
    for (int k = 0; k < 250; ++k) {  // 5 s of motor outputs at 50 Hz, the barometer at 25 Hz
      if (k % 2 == 0) f.estimator.addInput(pe::input::Scalar::kStaticPressure, f.t, 101325.0 - 1.2250 * 9.80665 * rate_m_s * (f.t - 100.0));
      f.fly(1690.0, 0.02);
    }
    return f.estimator.output();
  };
  const pe::EstimatorOutput climbing = climb(1.0);
  EXPECT_EQ(climbing.hover.blocker, pe::HoverBlocker::kClimbingOrSinking);
  EXPECT_EQ(climbing.vertical_speed_source, pe::VerticalSpeedSource::kBarometer);
  EXPECT_NEAR(climbing.hover.max_abs_vertical_speed_m_s, 1.0, 0.05);
  const pe::EstimatorOutput level = climb(0.0);
  EXPECT_TRUE(level.hover.hovering);
  EXPECT_EQ(level.hover.inactiveChecks(), pe::kTiltCheck | pe::kVerticalAccelCheck);

  // Velocity, when fresh, is preferred.
  EstimatorFixture f;
  f.estimator.addVerticalSpeed(f.t, 0.1);
  f.estimator.addInput(pe::input::Scalar::kStaticPressure, f.t, 101325.0);
  f.fly(1690.0, 0.1);
  EXPECT_EQ(f.estimator.output().vertical_speed_source, pe::VerticalSpeedSource::kVelocity);
}

TEST(Estimator, ASignalLostInTheWindowLeavesItUnjudged) {
  EstimatorFixture f;
  for (int k = 0; k < 100; ++k) {  // 2 s with a velocity, then it stops
    f.estimator.addVerticalSpeed(f.t, 0.0);
    f.fly(1690.0, 0.02);
  }
  EXPECT_TRUE(f.estimator.output().hover.hovering);
  f.fly(1690.0, 1.0);  // velocity stale after 0.5 s: part of the window has none
  EXPECT_EQ(f.estimator.output().hover.blocker, pe::HoverBlocker::kSignalGap);
  // 0.5 s (velocity/timeout_s) of the last second still had it: 24 of the window's 50 Hz samples.
  const std::string gap =
      "not hovering: a check's signal is missing on part of the window (tilt on 0, vertical speed on 74, "
      "vertical acceleration on 0 of 99 samples)";
  EXPECT_EQ(f.estimator.describeHover().substr(0, gap.size()), gap);
  f.fly(1690.0, 2.0);  // the whole window without: hover again, the check inactive
  EXPECT_TRUE(f.estimator.output().hover.hovering);
  EXPECT_EQ(f.estimator.output().hover.inactiveChecks(), pe::kTiltCheck | pe::kVerticalSpeedCheck | pe::kVerticalAccelCheck);
}
