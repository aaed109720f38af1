#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "estimator_fixture.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/estimation/tare_verdict.h"
#include "propulsion_estimator/onboard/health_summary.h"

namespace {

constexpr int kRcOut = static_cast<int>(pe::NodeInput::kRcOut);

pe::HealthConfig nodeConfig() {
  pe::HealthConfig config;
  config.battery_input = "/mavros/battery";
  config.rc_out_input = "/mavros/rc/out";
  return config;
}

pe::HealthSnapshot snapshot(const pe::Estimator& estimator, double time_s, const pe::InputActivity& inputs = {}) {
  return pe::HealthSnapshot{time_s, inputs, estimator.counters()};
}

// The value a status shows under `key`; fails the test when there is none.
std::string valueOf(const pe::HealthStatus& status, const std::string& key) {
  for (const auto& [k, v] : status.values) {
    if (k == key) return v;
  }
  ADD_FAILURE() << "no value '" << key << "' in status '" << status.message << "'";
  return "";
}

// What the node has counted when `count` RCOut messages have arrived.
pe::InputActivity rcOutReceived(std::uint64_t count) {
  pe::InputActivity inputs;
  inputs.received[kRcOut] = count;
  return inputs;
}

}  // namespace

TEST(HealthSummary, InputsErrorBeforeAnyBatteryVoltage) {
  EstimatorFixture f;
  const pe::HealthStatus status =
      pe::judgeInputs(f.estimator, snapshot(f.estimator, 0.0), snapshot(f.estimator, 1.0, rcOutReceived(50)), nodeConfig());
  EXPECT_EQ(status.level, pe::HealthLevel::kError);
  EXPECT_EQ(status.message, "estimates stopped: no valid battery voltage received on /mavros/battery");
  EXPECT_EQ(valueOf(status, "battery age (s)"), "inf");
}

TEST(HealthSummary, InputsErrorWhenTheBatteryIsStale) {
  EstimatorFixture f;
  f.estimator.addBattery(50.0, 11.4);
  const pe::HealthStatus status = pe::judgeInputs(f.estimator, snapshot(f.estimator, 59.0),
                                                  snapshot(f.estimator, 60.0, rcOutReceived(50)), nodeConfig());
  EXPECT_EQ(status.level, pe::HealthLevel::kError);
  EXPECT_EQ(status.message, "estimates stopped: no battery voltage for 10 s (limit 5 s) on /mavros/battery");
  EXPECT_EQ(valueOf(status, "battery age (s)"), "10");
}

TEST(HealthSummary, InputsWarnWithoutMotorOutputsAndTakeAnyRate) {
  EstimatorFixture f;
  f.estimator.addBattery(50.0, 11.4);
  const pe::InputActivity before = rcOutReceived(100);
  const pe::HealthStatus silent = pe::judgeInputs(f.estimator, snapshot(f.estimator, 50.0, before),
                                                  snapshot(f.estimator, 51.0, before), nodeConfig());
  EXPECT_EQ(silent.level, pe::HealthLevel::kWarn);
  EXPECT_EQ(silent.message, "no motor outputs on /mavros/rc/out");

  // The windows are sized by time: 1000 Hz is as good as 50 Hz.
  const pe::HealthStatus fast = pe::judgeInputs(f.estimator, snapshot(f.estimator, 50.0, before),
                                                snapshot(f.estimator, 51.0, rcOutReceived(1100)), nodeConfig());
  EXPECT_EQ(fast.level, pe::HealthLevel::kOk);
  EXPECT_EQ(fast.message, "receiving");
  EXPECT_EQ(valueOf(fast, "rc_out rate (Hz)"), "1000");
}

TEST(HealthSummary, InputsOkWhenReceivingWithRatesPerInput) {
  EstimatorFixture f;
  f.estimator.addBattery(50.0, 11.4);
  pe::InputActivity now = rcOutReceived(50);
  now.received[static_cast<int>(pe::NodeInput::kBattery)] = 1;
  now.received[static_cast<int>(pe::NodeInput::kImu)] = 100;
  now.imu_without_orientation = 3;
  const pe::HealthStatus status =
      pe::judgeInputs(f.estimator, snapshot(f.estimator, 50.0), snapshot(f.estimator, 52.0, now), nodeConfig());
  EXPECT_EQ(status.level, pe::HealthLevel::kOk);
  EXPECT_EQ(status.message, "receiving");
  EXPECT_EQ(valueOf(status, "rc_out rate (Hz)"), "25");
  EXPECT_EQ(valueOf(status, "battery rate (Hz)"), "0.5");
  EXPECT_EQ(valueOf(status, "imu rate (Hz)"), "50");
  EXPECT_EQ(valueOf(status, "velocity rate (Hz)"), "0");
  EXPECT_EQ(valueOf(status, "battery age (s)"), "2");
  EXPECT_EQ(valueOf(status, "imu messages without orientation"), "3");
}

TEST(HealthSummary, MotorOutputsWarnWithTheRefusalOfThePeriodThenRecover) {
  EstimatorFixture f;
  f.fly(1690.0, 1.0);
  const pe::HealthSnapshot start = snapshot(f.estimator, f.t);
  const std::vector<std::uint16_t> three(3, 1690);
  pe::InputActivity inputs;
  inputs.last_rc_out_verdict = f.estimator.addMotorOutputs(f.t, f.t, three.data(), three.size());
  const pe::HealthSnapshot refused = snapshot(f.estimator, f.t + 1.0, inputs);
  const pe::HealthStatus status = pe::judgeMotorOutputs(f.estimator, start, refused, nodeConfig());
  EXPECT_EQ(status.level, pe::HealthLevel::kWarn);
  EXPECT_EQ(status.message, "motor outputs ignored: RCOut has 3 channels, motor channel 4 is configured");
  EXPECT_EQ(valueOf(status, "rejected too_few_channels"), "1");
  EXPECT_EQ(valueOf(status, "rejected bad_imu"), "0");
  EXPECT_EQ(valueOf(status, "accepted"), "50");
  EXPECT_EQ(valueOf(status, "last rejection"), status.message);

  // The next period has no new refusal: OK again, the refusal still shown as the last one.
  f.t += 1.0;
  f.fly(1690.0, 1.0);
  inputs.last_rc_out_verdict = pe::Rejection::kNone;
  const pe::HealthStatus next =
      pe::judgeMotorOutputs(f.estimator, refused, snapshot(f.estimator, f.t, inputs), nodeConfig());
  EXPECT_EQ(next.level, pe::HealthLevel::kOk);
  EXPECT_EQ(next.message, "ok");
  EXPECT_EQ(valueOf(next, "last rejection"), status.message);
}

TEST(HealthSummary, MotorOutputsOkWithTheReasonWhileDisarmed) {
  EstimatorFixture f;
  f.fly(1690.0, 1.0);
  const pe::HealthSnapshot start = snapshot(f.estimator, f.t);
  const std::vector<std::uint16_t> disarmed(8, 900);
  pe::InputActivity inputs;
  inputs.last_rc_out_verdict = f.estimator.addMotorOutputs(f.t, f.t, disarmed.data(), disarmed.size());
  const pe::HealthStatus status =
      pe::judgeMotorOutputs(f.estimator, start, snapshot(f.estimator, f.t + 1.0, inputs), nodeConfig());
  EXPECT_EQ(status.level, pe::HealthLevel::kOk);
  EXPECT_EQ(status.message,
            "motor outputs ignored: channel 1 at 900 us, at or below disarmed_pwm_max_us 950 (disarmed or stopped)");
  EXPECT_EQ(valueOf(status, "rejected disarmed"), "1");
}

TEST(HealthSummary, MotorOutputsErrorForAnUndecodableMessageInThePeriod) {
  EstimatorFixture f;
  f.fly(1690.0, 1.0);
  const pe::HealthSnapshot start = snapshot(f.estimator, f.t);
  pe::InputActivity inputs;
  inputs.rc_out_undecodable = 1;
  inputs.last_decoding_error = "expected mavros_msgs/RCOut, got std_msgs/String";
  const pe::HealthSnapshot now = snapshot(f.estimator, f.t + 1.0, inputs);
  const pe::HealthStatus status = pe::judgeMotorOutputs(f.estimator, start, now, nodeConfig());
  EXPECT_EQ(status.level, pe::HealthLevel::kError);
  EXPECT_EQ(status.message, "/mavros/rc/out: expected mavros_msgs/RCOut, got std_msgs/String");
  EXPECT_EQ(valueOf(status, "rejected undecodable"), "1");
  EXPECT_EQ(valueOf(status, "last decoding error"), inputs.last_decoding_error);
  // A later period without another one is not an error any more.
  EXPECT_EQ(pe::judgeMotorOutputs(f.estimator, now, now, nodeConfig()).level, pe::HealthLevel::kOk);
}

TEST(HealthSummary, DomainWarnsAboveTheConfiguredShareOutside) {
  EstimatorFixture f;
  f.fly(1690.0, 1.0);
  const pe::HealthSnapshot inside = snapshot(f.estimator, f.t);
  const pe::HealthStatus ok = pe::judgeDomain(f.estimator, snapshot(f.estimator, 0.0), inside, nodeConfig());
  EXPECT_EQ(ok.level, pe::HealthLevel::kOk);
  EXPECT_EQ(ok.message, "within the measured domain");
  EXPECT_EQ(valueOf(ok, "fraction outside domain"), "0");

  f.fly(1950.0, 1.0);  // above the model's 1900 us; the thesis model clamps
  const pe::HealthStatus outside =
      pe::judgeDomain(f.estimator, inside, snapshot(f.estimator, f.t), nodeConfig());
  EXPECT_EQ(outside.level, pe::HealthLevel::kWarn);
  EXPECT_EQ(outside.message, "100 % of motor samples outside the model's domain (clamped)");
  EXPECT_EQ(valueOf(outside, "fraction outside domain"), "1");
  EXPECT_EQ(valueOf(outside, "samples outside domain (total)"), "200");

  EXPECT_EQ(valueOf(outside, "domain"), "1200-1900 us, 10.5-12.6 V");

  pe::HealthConfig tolerant = nodeConfig();
  tolerant.domain_warn_fraction = 1.0;
  EXPECT_EQ(pe::judgeDomain(f.estimator, inside, snapshot(f.estimator, f.t), tolerant).level, pe::HealthLevel::kOk);
}

TEST(HealthSummary, AModelWithoutCurrentIsNoWarningAndItsMissingOutputsAreNamed) {
  pe::Estimator estimator(thrustOnlyThesisModel(), pe::Vehicle::quadX(0.225), pe::EstimatorConfig{});
  estimator.addBattery(0.0, 11.4);
  const pe::HealthSnapshot before = snapshot(estimator, 0.0);
  const std::vector<std::uint16_t> hover(4, 1690);
  pe::InputActivity inputs = rcOutReceived(50);
  for (int k = 1; k <= 50; ++k) {
    inputs.last_rc_out_verdict = estimator.addMotorOutputs(0.02 * k, 0.02 * k, hover.data(), 4);
  }
  const pe::HealthSnapshot now = snapshot(estimator, 1.0, inputs);
  const pe::HealthStatus outputs = pe::judgeMotorOutputs(estimator, before, now, nodeConfig());
  EXPECT_EQ(outputs.level, pe::HealthLevel::kOk);
  EXPECT_EQ(outputs.message, "ok");
  EXPECT_EQ(valueOf(outputs, "accepted"), "50");
  EXPECT_EQ(valueOf(outputs, "rejected non_finite_estimate"), "0");
  const pe::HealthStatus domain = pe::judgeDomain(estimator, before, now, nodeConfig());
  EXPECT_EQ(domain.level, pe::HealthLevel::kOk);
  EXPECT_EQ(valueOf(domain, "outputs not modelled (published as NaN)"), "current, power, efficiency");
  EstimatorFixture thesis;
  EXPECT_EQ(valueOf(pe::judgeDomain(thesis.estimator, before, before, nodeConfig()),
                    "outputs not modelled (published as NaN)"),
            "none");
}

TEST(HealthSummary, PayloadIsOkWhenEveryHoverCheckHasItsSignal) {
  EstimatorFixture f;
  for (int k = 0; k < 200; ++k) {
    f.estimator.addImu(f.t, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.0, 0.0, pe::kStandardGravity));
    f.estimator.addVerticalSpeed(f.t, 0.0);
    f.fly(1690.0, 0.02);
  }
  const pe::HealthStatus status = pe::judgePayload(f.estimator);
  EXPECT_EQ(status.level, pe::HealthLevel::kOk);
  EXPECT_EQ(status.message, "no_tare_yet");
  EXPECT_EQ(valueOf(status, "hover checks inactive"), "none");
  EXPECT_EQ(valueOf(status, "vertical speed source"), "velocity");
}

TEST(HealthSummary, PayloadWarnsNamingTheInactiveHoverChecks) {
  EstimatorFixture f;
  f.fly(1690.0, 4.0);
  const pe::HealthStatus status = pe::judgePayload(f.estimator);
  // The fixture flies on PWM and voltage alone: every check that needs a signal is inactive.
  EXPECT_EQ(status.level, pe::HealthLevel::kWarn);
  EXPECT_EQ(status.message,
            "no_tare_yet; hover checks inactive: tilt, vertical speed, vertical acceleration (no fresh IMU, no fresh "
            "velocity or barometer)");
  EXPECT_EQ(valueOf(status, "hover checks inactive"), "tilt, vertical speed, vertical acceleration");
  EXPECT_EQ(valueOf(status, "vertical speed source"), "none");
  EXPECT_EQ(valueOf(status, "state"), "no_tare_yet");
  EXPECT_EQ(valueOf(status, "hovering"), "True");
  EXPECT_EQ(valueOf(status, "empty mass source"), "none");
  EXPECT_EQ(valueOf(status, "payload mass (kg)"), "nan");
  EXPECT_EQ(valueOf(status, "hover").rfind("hovering; window", 0), 0u) << valueOf(status, "hover");
}

TEST(HealthSummary, TareNeedsAHoverAndEnoughSamples) {
  pe::EstimatorConfig config;
  config.payload.min_samples = 200;
  EstimatorFixture f(config);
  f.fly(1690.0, 1.0);  // the hover window is not full yet
  const pe::EstimatorOutput& out = f.estimator.output();
  const pe::TareVerdict filling = pe::judgeTare(out.hover, out.payload, f.estimator.config());
  EXPECT_FALSE(filling.accepted);
  EXPECT_EQ(filling.refusal, "refused: " + f.estimator.describeHover());
  EXPECT_EQ(filling.refusal.rfind("refused: not hovering: window spans 0.98 s of the 1.6 s needed", 0), 0u)
      << filling.refusal;

  f.fly(1690.0, 2.0);  // hovering for about 1.4 s: 70 samples of the 200 needed
  ASSERT_TRUE(out.hover.hovering);
  const pe::TareVerdict few = pe::judgeTare(out.hover, out.payload, f.estimator.config());
  EXPECT_FALSE(few.accepted);
  EXPECT_EQ(few.refusal, "refused: hovering, but only " + std::to_string(out.payload.window_samples) +
                             " of the 200 hover samples needed are averaged yet");
  EXPECT_LT(out.payload.window_samples, 200u);
  EXPECT_EQ(f.estimator.tare(f.t).message, few.refusal);

  f.fly(1690.0, 4.0);
  const pe::TareVerdict ready = pe::judgeTare(out.hover, out.payload, f.estimator.config());
  EXPECT_TRUE(ready.accepted);
  EXPECT_EQ(ready.refusal, "");
  EXPECT_TRUE(f.estimator.tare(f.t).ok);
}

TEST(HealthSummary, ConfigRefusesAShareOutsideZeroToOne) {
  pe::HealthConfig config;
  EXPECT_NO_THROW(config.validate());
  for (const auto& [value, text] :
       std::vector<std::pair<double, std::string>>{{1.5, "domain_warn_fraction: 1.5 is outside 0..1"},
                                                   {-0.1, "domain_warn_fraction: -0.1 is outside 0..1"},
                                                   {std::nan(""), "domain_warn_fraction: nan is outside 0..1"}}) {
    config.domain_warn_fraction = value;
    try {
      config.validate();
      ADD_FAILURE() << "accepted " << value;
    } catch (const pe::ConfigError& e) {
      EXPECT_EQ(std::string(e.what()), text);
    }
  }
}

TEST(HealthSummary, DomainWarningSaysTheSamplesWereExtrapolated) {
  std::string text = pe::readTextFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  const std::string clamp = "outside: clamp";
  ASSERT_NE(text.find(clamp), std::string::npos);
  text.replace(text.find(clamp), clamp.size(), "outside: extrapolate");
  const pe::PropulsionModel extrapolating = pe::parseModelYaml(text, "extrapolating thesis model");
  pe::Estimator estimator(extrapolating, pe::Vehicle::quadX(0.225), pe::EstimatorConfig{});
  estimator.addBattery(0.0, 11.4);
  const pe::HealthSnapshot before = snapshot(estimator, 0.0);
  const std::vector<std::uint16_t> channels(4, 1950);  // above the model's 1900 us
  ASSERT_EQ(estimator.addMotorOutputs(0.02, 0.02, channels.data(), channels.size()), pe::Rejection::kNone);
  const pe::HealthStatus status = pe::judgeDomain(estimator, before, snapshot(estimator, 1.0), nodeConfig());
  EXPECT_EQ(status.level, pe::HealthLevel::kWarn);
  EXPECT_EQ(status.message, "100 % of motor samples outside the model's domain (extrapolated)");
}

TEST(HealthSummary, EffectsNoneForAPlainModel) {
  EstimatorFixture f;
  const pe::HealthStatus status =
      pe::judgeEffects(f.estimator, snapshot(f.estimator, 0.0), snapshot(f.estimator, 1.0), nodeConfig());
  EXPECT_EQ(status.level, pe::HealthLevel::kOk);
  EXPECT_EQ(status.message, "none: the model has no effects");
  EXPECT_TRUE(status.values.empty());
}

TEST(HealthSummary, EffectsWarnNamingEachCorrectionSkippedForItsSignal) {
  pe::effects::ModelEffects effects;
  effects.setParameter(pe::effects::Kind::kSupplyResistance, 0.04);
  effects.setParameter(pe::effects::Kind::kGroundEffect, 0.0011);
  effects.rotor_height_m = 0.05;
  effects.setParameter(pe::effects::Kind::kThrustLoss, 0.03);
  EstimatorFixture f({}, pe::Vehicle::quadX(0.225), effects);
  pe::HealthConfig config = nodeConfig();
  config.signal_sources.inputs[pe::input::index(pe::input::Scalar::kRangefinder)] = "/mavros/rangefinder/rangefinder";
  const pe::HealthSnapshot start = snapshot(f.estimator, f.t);
  f.estimator.addBatteryCurrent(f.t, -15.0);
  f.fly(1690.0, 0.1);  // no rangefinder yet
  const pe::HealthStatus missing = pe::judgeEffects(f.estimator, start, snapshot(f.estimator, f.t), config);
  EXPECT_EQ(missing.level, pe::HealthLevel::kWarn);
  EXPECT_EQ(missing.message,
            "skipped: ground_effect (height above the ground on /mavros/rangefinder/rangefinder missing or stale); "
            "applied: supply_resistance, thrust_loss");
  EXPECT_EQ(valueOf(missing, "ground_effect"),
            "coefficient_m2 0.0011, rotor_height_m 0.05; applied to 0, skipped on 5 messages since the last report; "
            "height above the ground on /mavros/rangefinder/rangefinder missing or stale");
  EXPECT_EQ(valueOf(missing, "supply_resistance"),
            "resistance_ohm 0.04; applied to 5, skipped on 0 messages since the last report");

  // Fresh now, but skipped earlier in the period: still a warning for this period.
  const pe::HealthSnapshot before = snapshot(f.estimator, f.t);
  f.fly(1690.0, 0.1);
  f.estimator.addRange(f.t, 1.0, 0.1, 12.0);
  const pe::HealthStatus late = pe::judgeEffects(f.estimator, before, snapshot(f.estimator, f.t), config);
  EXPECT_EQ(late.level, pe::HealthLevel::kWarn);
  EXPECT_EQ(late.message,
            "skipped: ground_effect (height above the ground on /mavros/rangefinder/rangefinder missing or stale); "
            "applied: supply_resistance, thrust_loss");

  // A period with the rangefinder fresh throughout.
  const pe::HealthSnapshot next = snapshot(f.estimator, f.t);
  f.fly(1690.0, 0.02);
  const pe::HealthStatus ok = pe::judgeEffects(f.estimator, next, snapshot(f.estimator, f.t), config);
  EXPECT_EQ(ok.level, pe::HealthLevel::kOk);
  EXPECT_EQ(ok.message, "applied: supply_resistance, ground_effect, thrust_loss");
}
