// The onboard session (issue 34): what estimator_node and every offline replay drive alike. Its
// readers judge at the time they are asked (a hover whose inputs stopped is over), it takes a
// signal only where an effect of the model reads it, and it refuses an rpm mass view it cannot give.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/onboard/esc_telemetry_health.h"
#include "propulsion_estimator/onboard/onboard_session.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

pe::PropulsionModel thesisModel() { return pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml")); }

pe::OnboardConfig quadConfig() {
  pe::OnboardConfig config;
  config.estimator.motor_channels = {1, 2, 3, 4};
  return config;
}

// A steady hover at `pwm` for `seconds` at 50 Hz from `*t`, a fresh voltage every second.
void hover(pe::OnboardSession* session, double* t, double seconds, double pwm = 1500.0) {
  const std::vector<std::uint16_t> channels(4, static_cast<std::uint16_t>(pwm));
  double last_battery = -10.0;
  for (const double end = *t + seconds; *t < end - 1e-9; *t += 0.02) {
    if (*t - last_battery >= 1.0) {
      session->addBattery(*t, 11.4, pe::kNaN, pe::kNaN);
      last_battery = *t;
    }
    ASSERT_EQ(session->addMotorOutputs(*t, *t, channels.data(), channels.size()), pe::Rejection::kNone) << *t;
  }
}

}  // namespace

TEST(OnboardSession, RefusesTheRpmMassViewOnAModelWithoutThrustFromRpm) {
  pe::OnboardConfig config = quadConfig();
  config.mass_view = "rpm";
  try {
    pe::OnboardSession session(thesisModel(), pe::Vehicle::quadX(0.225), config, "e300.yaml");
    FAIL() << "accepted";
  } catch (const pe::ConfigError& e) {
    EXPECT_STREQ(e.what(), "esc_telemetry/mass_view: rpm, but e300.yaml has no thrust_from_rpm (fit_surfaces writes "
                           "it from bench logs with an rpm column)");
  }
}

TEST(OnboardSession, EveryVerdictIsJudgedAtTheTimeItIsAskedFor) {
  pe::OnboardSession session(thesisModel(), pe::Vehicle::quadX(0.225), quadConfig());
  double t = 100.0;
  hover(&session, &t, 8.0);
  EXPECT_TRUE(session.detectHover(t).first);
  EXPECT_EQ(session.payloadHealth(t).values.empty(), false);
  EXPECT_GT(session.capability(t).capability.hover_mass_kg, 0.0);
  // No input for ten seconds: the hover is over whichever reader asks first, without being told to
  // expire it.
  EXPECT_FALSE(session.detectHover(t + 10.0).first);
  EXPECT_FALSE(session.estimator().output().hover.hovering);
}

TEST(OnboardSession, TakesASignalOnlyWhereAnEffectOfTheModelReadsIt) {
  const pe::Vehicle quad = pe::Vehicle::quadX(0.225);
  pe::OnboardSession plain(thesisModel(), quad, quadConfig());
  EXPECT_FALSE(plain.reads(pe::effects::Signal::kAirDensity));
  EXPECT_EQ(plain.addInput(pe::input::Scalar::kAirTemperature, 1.0, -100.0), pe::Rejection::kNone);  // dropped, as never subscribed
  EXPECT_EQ(plain.addInput(pe::input::Scalar::kMotorTemperature, 1.0, -100.0), pe::Rejection::kNone);

  pe::effects::ModelEffects fx = thesisModel().effects();
  fx.air_reference_density_kg_m3 = 1.2;
  fx.setParameter(pe::effects::Kind::kAirDensity, 1.0);
  pe::OnboardSession reading(thesisModel().withEffects(fx), quad, quadConfig());
  EXPECT_TRUE(reading.reads(pe::effects::Signal::kAirDensity));
  EXPECT_EQ(reading.addInput(pe::input::Scalar::kAirTemperature, 1.0, -100.0), pe::Rejection::kBadInput);
}

TEST(OnboardSession, ResetForgetsTheHoverAndTheChecks) {
  pe::OnboardSession session(thesisModel(), pe::Vehicle::quadX(0.225), quadConfig());
  double t = 100.0;
  hover(&session, &t, 8.0);
  ASSERT_FALSE(std::isnan(session.estimator().output().payload.total_mass_kg));
  session.reset();
  EXPECT_TRUE(std::isnan(session.estimator().output().payload.total_mass_kg));
  EXPECT_FALSE(session.motorHealth().judged);
  // Unjudged, the balance's figures are NaN (Capability.msg), not a balanced 0.
  EXPECT_TRUE(std::isnan(session.motorHealth().yaw_imbalance));
  EXPECT_TRUE(std::isnan(session.motorHealth().yaw_imbalance_std));
  EXPECT_TRUE(std::isnan(session.motorHealth().cg_offset_x_m));
  EXPECT_TRUE(std::isnan(session.motorHealth().cg_offset_y_m));
}

TEST(EscTelemetryHealth, SaysSoWhenNoTelemetryCameAndWhyNoneWasUsable) {
  pe::OnboardSession session(thesisModel(), pe::Vehicle::quadX(0.225), quadConfig());
  pe::EscInputActivity activity{"/mavros/esc_telemetry/telemetry, /mavros/esc_status/status", 0, 0, ""};
  pe::HealthStatus status = pe::judgeEscTelemetry(session, 1.0, activity);
  EXPECT_EQ(status.level, pe::HealthLevel::kOk);
  EXPECT_EQ(status.message, "no ESC telemetry: nothing measured, model check off, estimates unchanged");
  activity.received = activity.undecodable = 3;
  activity.last_error = "not a mavros_msgs/ESCStatus";
  status = pe::judgeEscTelemetry(session, 1.0, activity);
  EXPECT_EQ(status.message, "no usable ESC telemetry (not a mavros_msgs/ESCStatus): nothing measured, model check off");
  ASSERT_FALSE(status.values.empty());
  EXPECT_EQ(status.values[0].second, "/mavros/esc_telemetry/telemetry, /mavros/esc_status/status");
  EXPECT_EQ(status.values[2].second, "3");
}

namespace {

// A hover with ESC telemetry every 0.1 s (each rotor at `rpm`), the air given or not.
void hoverWithTelemetry(pe::OnboardSession* session, double* t, double seconds, bool air) {
  const std::vector<std::uint16_t> channels(4, 1500);
  for (const double end = *t + seconds; *t < end - 1e-9; *t += 0.02) {
    const int frame = static_cast<int>(std::lround(*t / 0.02));
    if (frame % 50 == 0) {
      session->addBattery(*t, 11.4, pe::kNaN, pe::kNaN);
      if (air) {
        session->addInput(pe::input::Scalar::kStaticPressure, *t, 90000.0);
        session->addInput(pe::input::Scalar::kAirTemperature, *t, 30.0);
      }
    }
    if (frame % 5 == 0) {
      pe::EscTelemetry message;
      message.stamp_s = *t;
      for (int k = 0; k < 4; ++k) {
        pe::EscReport esc;
        esc.stamp_s = *t;
        esc.rpm = 6000.0;
        esc.count = frame;
        message.escs.push_back(esc);
      }
      session->addEscTelemetry(*t, message);
    }
    ASSERT_EQ(session->addMotorOutputs(*t, *t, channels.data(), channels.size()), pe::Rejection::kNone) << *t;
  }
}

std::string valueOf(const pe::HealthStatus& status, const std::string& name) {
  for (const auto& [key, value] : status.values) {
    if (key == name) return value;
  }
  return "(absent)";
}

}  // namespace

// issue 36: the RPM view's mass at the bench's air, when the flight's is not known, says so in the
// diagnostics; with the air measured (a model whose air_density effect reads it) it does not.
TEST(EscTelemetryHealth, NamesTheBenchsAirWhereTheRpmViewHadNoOther) {
  pe::RpmThrust rpm_thrust;
  rpm_thrust.n_per_rpm2 = 1.1e-7;
  rpm_thrust.bench_air_density_kg_m3 = 1.2;
  const pe::EscInputActivity activity{"/mavros/esc_telemetry/telemetry, -", 100, 0, ""};
  const std::string label =
      "the bench's air density (no static pressure and air temperature): off by the density ratio on another day's air";

  pe::PropulsionModel bench_air = thesisModel();
  bench_air.setRpmThrust(rpm_thrust);
  pe::OnboardSession without(bench_air, pe::Vehicle::quadX(0.225), quadConfig());
  double t = 100.0;
  hoverWithTelemetry(&without, &t, 12.0, false);
  ASSERT_TRUE(without.rpmView());
  ASSERT_GT(without.rpmView()->hoverS(), 1.0);
  EXPECT_EQ(valueOf(pe::judgeEscTelemetry(without, t, activity), "rpm_view_air"), label);

  pe::effects::ModelEffects fx = thesisModel().effects();
  fx.air_reference_density_kg_m3 = 1.2;
  fx.setParameter(pe::effects::Kind::kAirDensity, 1.0);
  pe::PropulsionModel air_read = thesisModel().withEffects(fx);
  air_read.setRpmThrust(rpm_thrust);
  pe::OnboardSession with(air_read, pe::Vehicle::quadX(0.225), quadConfig());
  t = 100.0;
  hoverWithTelemetry(&with, &t, 12.0, true);
  ASSERT_GT(with.rpmView()->hoverS(), 1.0);
  EXPECT_FALSE(with.rpmView()->atBenchAir());
  EXPECT_EQ(valueOf(pe::judgeEscTelemetry(with, t, activity), "rpm_view_air"), "(absent)");
}
