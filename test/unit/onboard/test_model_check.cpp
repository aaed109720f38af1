// The live model check's rules on hand-made reports: repeats are not measurements, staleness, the
// verdicts from the deviations, the supply resistance's least squares.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/onboard/model_check.h"
#include "propulsion_estimator/onboard/rpm_mass_view.h"

namespace pe = propulsion_estimator;

namespace {

// Four motors modelled at 6000 rpm and 5 A, hovering.
pe::EstimatorOutput hoverOutput() {
  pe::EstimatorOutput out;
  out.hover.hovering = true;
  out.motors.resize(4);
  for (int k = 0; k < 4; ++k) {
    out.motors[k].channel = k + 1;
    out.motors[k].estimate.rpm = 6000.0;
    out.motors[k].estimate.current_a = 5.0;
    out.motors[k].estimate.in_domain = true;
  }
  return out;
}

// `seconds` of 50 Hz RCOut and 10 Hz telemetry with motor k at rpm 6000 x rpm[k] and 5 A x current[k].
void feed(pe::ModelCheck* check, double* t, double seconds, const double (&rpm)[4], const double (&current)[4],
          bool counted = true) {
  int count = 0;
  const pe::EstimatorOutput out = hoverOutput();
  for (int step = 0; step < static_cast<int>(seconds * 50.0); ++step) {
    *t += 0.02;
    check->addEstimate(*t, out);
    if (step % 5 != 0) continue;
    ++count;
    pe::EscTelemetry message;
    message.stamp_s = *t;
    for (int k = 0; k < 4; ++k) {
      // A little noise, so that reports without counts differ from one to the next.
      const double jitter = 1.0 + 1e-4 * ((count * 7 + k) % 5);
      message.escs.push_back({*t, 6000.0 * rpm[k] * jitter, 5.0 * current[k], 16.0, 30.0, counted ? count : -1});
    }
    check->addTelemetry(*t, message);
  }
}

}  // namespace

TEST(ModelCheck, NamesTheFamilyOfCauseFromTheDeviations) {
  struct Case {
    double rpm[4];
    double current[4];
    pe::ModelCheckVerdict verdict;
    int channel;
  };
  const Case cases[] = {
      {{1, 1, 1, 1}, {1, 1, 1, 1}, pe::ModelCheckVerdict::kConsistent, 0},
      // Faster, and less current than that speed needs (~ n^3): the propeller.
      {{1, 1.02, 1, 1}, {1, 0.97, 1, 1}, pe::ModelCheckVerdict::kPropeller, 2},
      // Slower, and more current than that speed needs: the motor or its ESC.
      {{1, 1, 0.97, 1}, {1, 1, 1.0, 1}, pe::ModelCheckVerdict::kMotorEsc, 3},
      // Faster with the current the speed needs: an error of the command, no cause named.
      {{1.02, 1, 1, 1}, {1.0612, 1, 1, 1}, pe::ModelCheckVerdict::kConsistent, 0},
      // Every motor alike, 4 % slow: the supply.
      {{0.96, 0.96, 0.96, 0.96}, {0.9, 0.9, 0.9, 0.9}, pe::ModelCheckVerdict::kSupply, 0},
  };
  for (const Case& c : cases) {
    pe::ModelCheck check({1, 2, 3, 4}, {});
    double t = 0.0;
    feed(&check, &t, 2.0, c.rpm, c.current);
    EXPECT_EQ(check.report(t).verdict, pe::ModelCheckVerdict::kNotJudged);  // 2 s of hover, 3 s needed
    feed(&check, &t, 3.0, c.rpm, c.current);
    const pe::ModelCheckReport report = check.report(t);
    EXPECT_EQ(report.verdict, c.verdict) << report.note;
    EXPECT_EQ(report.flagged_channel, c.channel) << report.note;
    EXPECT_EQ(report.fresh_motors, 4);
    EXPECT_NEAR(report.motors[1].hover_rpm_ratio, c.rpm[1], 2e-3);
  }
}

// rpm_tolerance and current_tolerance (0.9 % and 1 %) hold from both sides: a rotor 2 % fast that
// draws 0.75 % less current than that speed needs is consistent and one drawing 1.25 % less is a
// propeller; halving current_tolerance names the first, raising it by half clears the second.
// (rpm_tolerance: NoFlagOnTwoHundredFlightsWithoutAFault and the weak-propeller flights.)
TEST(ModelCheck, TheCurrentToleranceLiesBetweenTwoPropellerSignatures) {
  const auto verdict = [](double current_short, const pe::ModelCheckConfig& config) {
    pe::ModelCheck check({1, 2, 3, 4}, config);
    double t = 0.0;
    feed(&check, &t, 5.0, {1, 1.02, 1, 1}, {1, std::pow(1.02, 3) * (1.0 - current_short), 1, 1});
    return check.report(t).verdict;
  };
  pe::ModelCheckConfig config;
  EXPECT_EQ(verdict(0.0075, config), pe::ModelCheckVerdict::kConsistent);
  EXPECT_EQ(verdict(0.0125, config), pe::ModelCheckVerdict::kPropeller);
  const pe::ModelCheckConfig calibrated;
  config.current_tolerance = 0.5 * calibrated.current_tolerance;
  EXPECT_EQ(verdict(0.0075, config), pe::ModelCheckVerdict::kPropeller);
  config.current_tolerance = 1.5 * calibrated.current_tolerance;
  EXPECT_EQ(verdict(0.0125, config), pe::ModelCheckVerdict::kConsistent);
}

// Healthy motors differ by their parts: a propeller that turns a little more torque per thrust
// than the others shows the damaged propeller's signature on every flight. Against a baseline of
// the same vehicle's healthy flights only a change from it counts.
TEST(ModelCheck, JudgesEachMotorByItsChangeFromTheBaseline) {
  const double healthy_rpm[4] = {1, 1.02, 1, 1}, healthy_current[4] = {1, 0.97, 1, 1};
  pe::ModelCheck plain({1, 2, 3, 4}, {});
  double t = 0.0;
  feed(&plain, &t, 5.0, healthy_rpm, healthy_current);
  const pe::ModelCheckReport alone = plain.report(t);
  EXPECT_EQ(alone.verdict, pe::ModelCheckVerdict::kPropeller) << alone.note;

  pe::ModelCheck check({1, 2, 3, 4}, {});
  check.setBaseline({alone.motors[0].rpm_deviation, alone.motors[1].rpm_deviation, alone.motors[2].rpm_deviation,
                     alone.motors[3].rpm_deviation},
                    {alone.motors[0].current_deviation, alone.motors[1].current_deviation,
                     alone.motors[2].current_deviation, alone.motors[3].current_deviation});
  t = 0.0;
  feed(&check, &t, 5.0, healthy_rpm, healthy_current);
  EXPECT_EQ(check.report(t).verdict, pe::ModelCheckVerdict::kConsistent) << check.report(t).note;
  EXPECT_NEAR(check.report(t).motors[1].rpm_deviation, 0.0, 1e-3);

  // Motor 3's propeller damaged since: found, and named against its healthy flights.
  check.reset();
  const double damaged_rpm[4] = {1, 1.02, 1.02, 1}, damaged_current[4] = {1, 0.97, 0.97, 1};
  t = 0.0;
  feed(&check, &t, 5.0, damaged_rpm, damaged_current);
  const pe::ModelCheckReport report = check.report(t);
  EXPECT_EQ(report.verdict, pe::ModelCheckVerdict::kPropeller) << report.note;
  EXPECT_EQ(report.flagged_channel, 3) << report.note;
  EXPECT_NE(report.note.find("against the other motors and its healthy flights"), std::string::npos) << report.note;
}

// A vehicle whose every motor turns 3 % slower than the model says on its healthy flights (its
// parts, the day's air, warm motors) is no supply fault on every flight: against the level of its
// healthy flights only a change counts, and a further 3 % since is one.
TEST(ModelCheck, JudgesTheMotorsTogetherByTheirChangeFromTheHealthyLevel) {
  const double slow_rpm[4] = {0.97, 0.97, 0.97, 0.97}, slow_current[4] = {0.92, 0.92, 0.92, 0.92};
  pe::ModelCheck plain({1, 2, 3, 4}, {});
  double t = 0.0;
  feed(&plain, &t, 5.0, slow_rpm, slow_current);
  EXPECT_EQ(plain.report(t).verdict, pe::ModelCheckVerdict::kSupply) << plain.report(t).note;

  pe::ModelCheck check({1, 2, 3, 4}, {});
  check.setBaseline({0, 0, 0, 0}, {0, 0, 0, 0}, 0.97);
  t = 0.0;
  feed(&check, &t, 5.0, slow_rpm, slow_current);
  EXPECT_EQ(check.report(t).verdict, pe::ModelCheckVerdict::kConsistent) << check.report(t).note;

  check.reset();
  const double slower_rpm[4] = {0.94, 0.94, 0.94, 0.94}, slower_current[4] = {0.85, 0.85, 0.85, 0.85};
  t = 0.0;
  feed(&check, &t, 5.0, slower_rpm, slower_current);
  const pe::ModelCheckReport report = check.report(t);
  EXPECT_EQ(report.verdict, pe::ModelCheckVerdict::kSupply) << report.note;
  EXPECT_NE(report.note.find("(-3.0 % on its healthy flights)"), std::string::npos) << report.note;
  EXPECT_THROW(check.setBaseline({}, {}, 0.0), std::invalid_argument);
}

TEST(RpmMassView, SaysWhenTheBenchsAirStoodInForTheFlights) {
  pe::ModelCheck check({1, 2, 3, 4}, {});
  double t = 0.0;
  const double alike[4] = {1, 1, 1, 1};
  feed(&check, &t, 5.0, alike, alike);
  pe::EstimatorOutput out = hoverOutput();
  out.totals.thrust_n = 4 * 6.0;
  out.totals.mass_kg = 4 * 6.0 / 9.81;
  pe::RpmThrust thrust;
  thrust.n_per_rpm2 = 6.0 / (6000.0 * 6000.0);
  thrust.bench_air_density_kg_m3 = 1.2;
  pe::RpmMassView view(thrust, 3.0);
  view.add(t, out, check, 1.1);
  EXPECT_FALSE(view.atBenchAir());
  EXPECT_NEAR(view.massKg(), out.totals.mass_kg * 1.1 / 1.2, 0.01);
  view.add(t + 0.02, out, check, pe::kNaN);
  EXPECT_TRUE(view.atBenchAir());
  view.reset();
  EXPECT_FALSE(view.atBenchAir());
}

TEST(ModelCheck, RefusesABaselineOfAnotherMotorCount) {
  pe::ModelCheck check({1, 2, 3, 4}, {});
  try {
    check.setBaseline({0.0, 0.0}, {0.0, 0.0});
    FAIL() << "a baseline of 2 motors was accepted for 4";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "ESC baseline: 2 rpm and 2 current deviations for 4 rotors");
  }
  EXPECT_THROW(check.setBaseline({0, 0, 0, 0}, {}), std::invalid_argument);
  EXPECT_NO_THROW(check.setBaseline({}, {}));
}

TEST(ModelCheck, ARepeatedReportIsNotAMeasurementAndGoesStale) {
  pe::ModelCheck check({1, 2, 3, 4}, {});
  EXPECT_EQ(check.report(0.0).note, "no ESC telemetry received");
  EXPECT_TRUE(std::isnan(check.report(0.0).motors[0].measured_rpm));
  pe::EscTelemetry message;
  message.escs.assign(4, {0.0, 6000.0, 5.0, 16.0, 30.0, 7});
  check.addTelemetry(1.0, message);
  EXPECT_EQ(check.report(1.0).fresh_motors, 4);
  EXPECT_EQ(check.report(1.0).motors[2].measured_rpm, 6000.0);
  // The autopilot repeats the last packet (same count) for a second: stale after stale_after_s.
  for (double t = 1.1; t < 2.0; t += 0.1) check.addTelemetry(t, message);
  EXPECT_EQ(check.report(2.0).fresh_motors, 0);
  EXPECT_TRUE(std::isnan(check.report(2.0).motors[2].measured_rpm));
  EXPECT_TRUE(std::isnan(check.report(2.0).motors[2].current_ratio));
  // ESCs beyond the rotors' channels are ignored.
  message.escs.assign(8, {0.0, 6000.0, 5.0, 16.0, 30.0, 8});
  check.addTelemetry(2.1, message);
  EXPECT_EQ(check.report(2.1).fresh_motors, 4);
}

TEST(ModelCheck, WorksWithoutPacketCounts) {
  pe::ModelCheck check({1, 2, 3, 4}, {});
  double t = 0.0;
  feed(&check, &t, 5.0, {1, 1.02, 1, 1}, {1, 0.97, 1, 1}, false);
  EXPECT_EQ(check.report(t).verdict, pe::ModelCheckVerdict::kPropeller);
}

TEST(ModelCheck, RefusesABadConfig) {
  pe::ModelCheckConfig config;
  config.window_s = 0.0;
  EXPECT_THROW(pe::ModelCheck({1, 2, 3, 4}, config), pe::FieldError);
  try {
    pe::ModelCheck({1}, config);
    FAIL() << "a zero window_s was accepted";
  } catch (const pe::FieldError& e) {
    EXPECT_NE(std::string(e.what()).find("esc_telemetry/window_s"), std::string::npos) << e.what();
  }
}

TEST(SupplyResistanceEstimator, FindsTheSlopeOfTheDropAgainstTheCurrentWithAnOffset) {
  pe::SupplyResistanceEstimator estimator(60.0, 0.04);
  EXPECT_TRUE(std::isnan(estimator.resistanceOhm()));
  std::mt19937_64 random(3);
  std::normal_distribution<double> noise(0.0, 0.04);
  for (int k = 0; k < 120; ++k) {
    const double current = 10.0 + 15.0 * std::sin(0.3 * k) * std::sin(0.3 * k);
    estimator.add(k, 0.12 + 0.03 * current + noise(random), current);
  }
  EXPECT_NEAR(estimator.resistanceOhm(), 0.03, 0.003);
  EXPECT_GT(estimator.resistanceStdOhm(), 0.0);
  EXPECT_LT(estimator.resistanceStdOhm(), 0.003);
  // A steady current identifies nothing new: the uncertainty does not shrink below what it was.
  const double before = estimator.resistanceStdOhm();
  for (int k = 120; k < 400; ++k) estimator.add(k, 0.12 + 0.03 * 10.0 + noise(random), 10.0);
  EXPECT_GT(estimator.resistanceStdOhm(), before);
  estimator.add(399.0, 1.0, 10.0);  // not after the last: ignored
  estimator.add(400.0, std::nan(""), 10.0);
  EXPECT_EQ(estimator.samples(), 400);
}
