#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/gap/blocks.h"
#include "propulsion_estimator/gap/diagnosis.h"
#include "propulsion_estimator/gap/gap_report.h"
#include "propulsion_estimator/gap/motor_balance.h"
#include "propulsion_estimator/gap/thrust_views.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/offline/flight_estimate.h"
#include "propulsion_estimator/offline/flight_feed.h"
#include "model_variants.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;
namespace gap = propulsion_estimator::gap;
using pe::effects::Kind;

namespace {

// The world a synthetic flight is flown in: the thesis surfaces are the truth of the propulsion
// chain, and one cause (or none) sits between them and the flight.
struct World {
  double thrust_loss = 0.0;        // fraction of thrust the airframe takes
  double supply_resistance = 0.0;  // ohm between the voltage sensor and the ESCs
  double esc_offset_us = 0.0;      // the flying ESCs need this much more pulse width
  int weak_motor = -1;             // index of a motor whose propeller gives weak_factor of its thrust
  double weak_factor = 1.0;
  bool kicks = false;              // every 10 s the autopilot kicks the PWM up for 0.3 s; the rotors lag
  // With kicks, the vehicle lifts with each kick this long after it (a pure delay, which no
  // first-order lag matches); negative: the kicks lift nothing.
  double kick_lift_delay_s = -1.0;
  double kick_us = 60.0;           // how far each kick lifts the PWM
  double current_noise_a = 0.0;    // standard deviation of each battery current reading, A
  double avionics_a = 0.0;         // drawn beside the motors: on the battery current, turning no rotor
  bool telemetry = false;          // ESC telemetry: each rotor's speed at 10 Hz, 1 % noise
  double one_mass_kg = 0.0;        // every hover at this mass (0: the flights' varied payloads)
  // Each flight's motors at their own temperature (the day's, 14-26 C), logged, and each rotor's
  // thrust at a given command (1 + motor_per_c (T - 22 C)): motor_temperature's own law.
  bool motor_temperature = false;
  double motor_per_c = 0.0;
  double motor_warming_c = 0.0;    // each flight's motors warm by this much, linearly over the flight
  bool warming_heats = false;      // the thrust follows the warming too (else only the day's temperature)
  bool day_heats = true;           // the thrust follows the day's temperature the motors start at
  bool no_current = false;         // no battery current logged
  // Each flight's rotors give (1 + flight_spread * a flight's own draw in -1.2..1) of their thrust:
  // what a payload's hang and the day do to one flight and not to the next.
  double flight_spread = 0.0;
};

// The rotors' thrust against speed, T = a n^2 (about 7000 rpm in hover), for the model and the
// synthetic telemetry alike.
constexpr double kNewtonPerRpm2 = 7.5e-8;

class SyntheticFlights : public ::testing::Test {
 protected:
  SyntheticFlights()
      : model_(pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"))),
        vehicle_(pe::Vehicle::quadX(0.225)),
        views_(model_, 4) {
    pe::RpmThrust rpm_thrust;
    rpm_thrust.n_per_rpm2 = kNewtonPerRpm2;
    model_.setRpmThrust(rpm_thrust);
  }

  // A pulse width giving `thrust_n` on one motor at `voltage_v` (bisection on the surfaces).
  double pwmFor(double thrust_n, double voltage_v) const {
    double low = 1100.0, high = 2000.0;
    for (int i = 0; i < 60; ++i) {
      const double middle = 0.5 * (low + high);
      (views_.surfaceThrust(middle, voltage_v) < thrust_n ? low : high) = middle;
    }
    return 0.5 * (low + high);
  }

  double motorCurrent(double pwm_us, double voltage_v) const {
    return model_.evaluateRaw(pe::Output::kCurrent, pwm_us, voltage_v);
  }

  // A flight of three 40 s hovers at the given masses, the battery sagging from `voltage_v`.
  pe::Flight fly(const std::string& name, const World& world, const std::vector<double>& masses, double voltage_v,
                  unsigned seed) const {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> force_noise(0.0, 0.3), pwm_noise(0.0, 2.0), current_noise(0.0, 1.0),
        rpm_noise(0.0, 0.01);
    pe::Flight flight;
    flight.name = name;
    flight.streams.source = name;
    flight.streams.motors = 4;
    const double motor_c = 14.0 + 3.0 * static_cast<double>(seed % 5);
    static const double kFlightDraw[] = {0.6, 1.0, -0.8, 0.4, -1.2};
    const double flight_factor = 1.0 + world.flight_spread * kFlightDraw[seed % 5];
    const auto warming_at = [&](double time_s) {
      return world.motor_warming_c * time_s / (47.0 * static_cast<double>(masses.size()));
    };
    // The autopilot's kick at `time_s`, us.
    const auto kickAt = [&](double time_s) {
      return world.kicks && std::fmod(time_s, 10.0) >= 5.0 && std::fmod(time_s, 10.0) < 5.3 ? world.kick_us : 0.0;
    };
    double t = 0.0;
    for (std::size_t s = 0; s < masses.size(); ++s) {
      const double mass = world.one_mass_kg > 0.0 ? world.one_mass_kg : masses[s];
      const double start = t + 2.0;
      for (int i = 0; i < 50 * 42; ++i, t += 0.02) {
        const double sensed = voltage_v - 0.3 * (t / 150.0);
        const double warm =
            (1.0 + world.motor_per_c * ((world.day_heats ? motor_c : 22.0) + (world.warming_heats ? warming_at(t) : 0.0) -
                                        22.0)) *
            flight_factor;
        // What the ESCs see and what each rotor must give so that the vehicle hovers.
        double esc_voltage = sensed;
        double current = 0.0;
        std::array<double, 4> pwm{};
        for (int pass = 0; pass < 3; ++pass) {
          current = 0.0;
          for (int k = 0; k < 4; ++k) {
            const double factor =
                (k == world.weak_motor ? world.weak_factor : 1.0) * (1.0 - world.thrust_loss) * warm;
            pwm[k] = pwmFor(mass * pe::kStandardGravity / 4.0 / factor, esc_voltage) + world.esc_offset_us;
            current += motorCurrent(pwm[k] - world.esc_offset_us, esc_voltage) *
                       (k == world.weak_motor ? std::pow(world.weak_factor, 1.5) : 1.0);
          }
          esc_voltage = sensed - world.supply_resistance * current;
        }
        pe::RcOutFrame frame;
        frame.time_s = t;
        const double kick = kickAt(t);
        for (int k = 0; k < 4; ++k) frame.pwm_us[k] = pwm[k] + kick + pwm_noise(rng);
        double lift_n = 0.0;
        if (world.kick_lift_delay_s >= 0.0 && kickAt(t - world.kick_lift_delay_s) > 0.0) {
          for (int k = 0; k < 4; ++k) {
            lift_n += views_.surfaceThrust(pwm[k] + world.kick_us, esc_voltage) - views_.surfaceThrust(pwm[k], esc_voltage);
          }
        }
        flight.streams.rc_out.push_back(frame);
        if (world.telemetry && i % 5 == 0) {
          // The rotor turns as fast as its own thrust (before the airframe takes its share) needs.
          pe::EscTelemetryReading esc;
          esc.time_s = t;
          esc.escs = 4;
          for (int k = 0; k < 4; ++k) {
            const double factor = (k == world.weak_motor ? world.weak_factor : 1.0) * (1.0 - world.thrust_loss);
            const double rotor_n = mass * pe::kStandardGravity / 4.0 / factor;
            esc.rpm[k] = std::sqrt(rotor_n / kNewtonPerRpm2) * (1.0 + rpm_noise(rng));
          }
          flight.streams.esc.push_back(esc);
        }
        if (i % 5 == 0) {
          const double sensed_current = world.no_current ? std::nan("")
                                                         : current + world.avionics_a + world.current_noise_a * current_noise(rng);
          flight.streams.battery.push_back({t, sensed, -sensed_current});  // PX4 through MAVROS: negated
          if (world.motor_temperature) {
            flight.streams.input(pe::input::Scalar::kMotorTemperature).push_back({t, motor_c + warming_at(t)});
          }
        }
        pe::ImuReading imu;
        imu.time_s = t;
        imu.specific_force_m_s2 = Eigen::Vector3d(0.0, 0.0, pe::kStandardGravity + lift_n / mass + force_noise(rng));
        flight.streams.imu.push_back(imu);
      }
      flight.segments.push_back({start, t - 1.0, mass});
      t += 5.0;
    }
    return flight;
  }

  // Five flights; `seed` 0: the same noise as every other call's, else their own.
  std::vector<pe::Flight> flights(const World& world, unsigned seed = 0) const {
    return {fly("f1.bag", world, {1.3, 1.6, 1.75}, 12.4, 1 + 10 * seed),
            fly("f2.bag", world, {1.35, 1.5, 1.8}, 11.8, 2 + 10 * seed),
            fly("f3.bag", world, {1.3, 1.7, 1.55}, 11.3, 3 + 10 * seed),
            fly("f4.bag", world, {1.45, 1.65, 1.4}, 12.2, 4 + 10 * seed),
            fly("f5.bag", world, {1.6, 1.35, 1.8}, 11.6, 5 + 10 * seed)};
  }

  gap::Diagnosis diagnose(const World& world, bool rpm_view = true) const {
    gap::DiagnosisConfig config;
    config.rpm_view = rpm_view;
    return gap::diagnoseGap(model_, vehicle_, flights(world), config);
  }

  pe::PropulsionModel model_;
  pe::Vehicle vehicle_;
  gap::ThrustViews views_;
};

}  // namespace

TEST_F(SyntheticFlights, NamesNothingWhenTheModelIsTheTruth) {
  const gap::Diagnosis diagnosis = diagnose(World{});
  EXPECT_TRUE(diagnosis.selected.empty());
  EXPECT_LT(std::abs(diagnosis.overall.bias_pct), 0.5);
  EXPECT_FALSE(diagnosis.motors.suspect_channel);
  EXPECT_EQ(diagnosis.transient_blocks, 0);
  for (const gap::EffectResult& effect : diagnosis.effects) {
    // Synthetic flights have neither height, vertical speed, air nor motor temperature.
    const bool needs_signal = pe::effects::requiredSignal(effect.kind) != pe::effects::Signal::kNone &&
                              effect.kind != Kind::kSupplyResistance;
    EXPECT_EQ(effect.testable, !needs_signal) << pe::effects::kindName(effect.kind);
  }
}

TEST_F(SyntheticFlights, LeavesOutTransientBlocksWhereTheRotorsLagThePwm) {
  World world;
  world.kicks = true;
  const gap::Diagnosis diagnosis = diagnose(world);
  // 5 flights x 3 hovers x 4 kicks, each touching one or two blocks.
  EXPECT_GE(diagnosis.transient_blocks, 40);
  EXPECT_LE(diagnosis.transient_blocks, 120);
  EXPECT_EQ(diagnosis.blocks, diagnosis.overall.samples);
  EXPECT_LT(std::abs(diagnosis.overall.bias_pct), 0.5);
  EXPECT_TRUE(diagnosis.selected.empty());
  EXPECT_NE(gap::gapReportMarkdown(diagnosis, model_, "cmd").find(
                std::to_string(diagnosis.transient_blocks) + " transient blocks"),
            std::string::npos);
}

TEST_F(SyntheticFlights, NamesAThrustLossAndShrinksTheGap) {
  World world;
  world.thrust_loss = 0.06;
  const gap::Diagnosis diagnosis = diagnose(world);
  ASSERT_EQ(diagnosis.selected, std::vector<Kind>{Kind::kThrustLoss});
  EXPECT_NEAR(*diagnosis.fitted.parameter(Kind::kThrustLoss), 0.06, 0.005);
  EXPECT_GT(diagnosis.overall.bias_pct, 5.0);
  EXPECT_LT(diagnosis.heldout.after_rmse_pct, 0.3 * diagnosis.heldout.before_rmse_pct);
}

TEST_F(SyntheticFlights, TellsASupplyResistanceFromAThrustLossByTheCurrent) {
  World world;
  world.supply_resistance = 0.08;
  const gap::Diagnosis diagnosis = diagnose(world);
  ASSERT_EQ(diagnosis.selected, std::vector<Kind>{Kind::kSupplyResistance});
  EXPECT_NEAR(*diagnosis.fitted.parameter(Kind::kSupplyResistance), 0.08, 0.01);
  EXPECT_LT(diagnosis.heldout.after_rmse_pct, 0.3 * diagnosis.heldout.before_rmse_pct);
}

TEST_F(SyntheticFlights, NamesAnEscOffset) {
  World world;
  world.esc_offset_us = 25.0;
  const gap::Diagnosis diagnosis = diagnose(world);
  ASSERT_EQ(diagnosis.selected, std::vector<Kind>{Kind::kEscOffset});
  EXPECT_NEAR(*diagnosis.fitted.parameter(Kind::kEscOffset), 25.0, 3.0);
}

// A noisy current sensor (2 A per reading, about 5 % of the thrust per block through the inverted
// surface) and the avionics' own 1.5 A: the current view cannot tell an ESC offset from a thrust
// loss (both shift its mean, like the avionics do), while the PWM view can. Its scatter, weighed
// as much as the PWM view's, left the ESC offset unnamed here (no joint fall significant);
// weighed by the noise, it does not outvote.
TEST_F(SyntheticFlights, ANoisyCurrentViewDoesNotOutvoteTheQuietPwmView) {
  World world;
  world.esc_offset_us = 25.0;
  world.current_noise_a = 2.0;
  world.avionics_a = 1.5;
  const gap::Diagnosis diagnosis = diagnose(world);
  EXPECT_LT(diagnosis.current_view_weight, 0.05);
  EXPECT_GT(diagnosis.current_view_weight, 0.0);
  ASSERT_EQ(diagnosis.selected, std::vector<Kind>{Kind::kEscOffset});
  EXPECT_NEAR(*diagnosis.fitted.parameter(Kind::kEscOffset), 25.0, 3.0);
  EXPECT_NE(diagnosis.method.find("the current view weighted by"), std::string::npos);
}

// Hovers at one mass: an ESC offset moves every block by nearly the same fraction, as a thrust
// loss does, and a noisy current sensor beside the avionics' own draw cannot tell them apart. The
// rotors' speeds can: an offset changes how fast they turn for a pulse width, not the thrust they
// give at that speed. Without the RPM view the offset is taken for a thrust loss.
TEST_F(SyntheticFlights, TheRpmViewTellsAnEscOffsetFromAThrustLossWhereTheCurrentCannot) {
  World world;
  world.esc_offset_us = 15.0;
  world.one_mass_kg = 1.5;
  world.current_noise_a = 3.0;
  world.avionics_a = 1.5;
  world.telemetry = true;
  const gap::Diagnosis without = diagnose(world, false);
  EXPECT_EQ(without.selected, std::vector<Kind>{Kind::kThrustLoss});
  EXPECT_EQ(without.rpm_view_blocks, 0);
  EXPECT_NE(without.method.find("the RPM view left out (--no-rpm-view)"), std::string::npos);
  const gap::Diagnosis with = diagnose(world);
  ASSERT_EQ(with.selected, std::vector<Kind>{Kind::kEscOffset});
  EXPECT_NEAR(*with.fitted.parameter(Kind::kEscOffset), 15.0, 3.0);
  EXPECT_EQ(with.rpm_view_blocks, with.blocks);
  EXPECT_GT(with.rpm_view_weight, 0.2);
  EXPECT_NE(with.method.find("the RPM view, each rotor's measured speed through thrust_from_rpm on"), std::string::npos);
}

// A regression guard, not the view's own merit: the other views already tell these two apart,
// and the RPM view (which sees the loss and not the resistance) must not blur them.
TEST_F(SyntheticFlights, WithTheRpmViewAThrustLossAndASupplyResistanceStayApart) {
  for (const bool loss : {true, false}) {
    World world;
    (loss ? world.thrust_loss : world.supply_resistance) = loss ? 0.03 : 0.06;
    world.one_mass_kg = 1.5;
    world.current_noise_a = 3.0;
    world.avionics_a = 1.5;
    world.telemetry = true;
    const gap::Diagnosis diagnosis = diagnose(world);
    EXPECT_EQ(diagnosis.selected, std::vector<Kind>{loss ? Kind::kThrustLoss : Kind::kSupplyResistance});
  }
}

TEST_F(SyntheticFlights, WithTelemetryNamesNothingWhenTheModelIsTheTruth) {
  World world;
  world.telemetry = true;
  EXPECT_TRUE(diagnose(world).selected.empty());
}

TEST_F(SyntheticFlights, PointsAtAWeakPropellerAndNamesNoEffect) {
  gap::DiagnosisConfig config;
  config.motor_reference = gap::learnReference(model_, vehicle_, flights(World{}), config);
  World world;
  world.weak_motor = 2;
  world.weak_factor = 0.85;
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, flights(world), config);
  ASSERT_TRUE(diagnosis.motors.suspect_channel);
  EXPECT_EQ(*diagnosis.motors.suspect_channel, 3);
  EXPECT_TRUE(diagnosis.selected.empty());
}

// A vehicle whose rotors give 4 % less than the bench unit's (its parts, its frame): without a
// reference that is a thrust loss; against its own healthy flights nothing changed, and a loss
// since is named at its own size, the corrected model carrying both.
TEST_F(SyntheticFlights, AgainstItsHealthyFlightsAVehicleIsJudgedByWhatChanged) {
  World built;
  built.thrust_loss = 0.04;
  built.telemetry = true;
  const gap::Diagnosis alone = gap::diagnoseGap(model_, vehicle_, flights(built), gap::DiagnosisConfig());
  EXPECT_EQ(alone.selected, std::vector<Kind>{Kind::kThrustLoss});

  gap::DiagnosisConfig config;
  config.motor_reference = gap::learnReference(model_, vehicle_, flights(built, 1), config);
  EXPECT_NEAR(config.motor_reference->thrust_factor, 0.96, 0.005);
  EXPECT_NEAR(config.motor_reference->current_thrust_factor, 0.96, 0.02);
  EXPECT_NEAR(config.motor_reference->rpm_thrust_factor, 0.96, 0.005);
  const gap::Diagnosis healthy = gap::diagnoseGap(model_, vehicle_, flights(built), config);
  EXPECT_TRUE(healthy.selected.empty()) << testing::PrintToString(healthy.problems);
  EXPECT_NEAR(healthy.motors.reference_thrust_factor, 0.96, 0.005);
  EXPECT_NEAR(*gap::correctedEffects(healthy).parameter(Kind::kThrustLoss), 0.04, 0.005);

  World worn = built;
  worn.thrust_loss = 1.0 - 0.96 * 0.94;  // 6 % lost since
  const gap::Diagnosis since = gap::diagnoseGap(model_, vehicle_, flights(worn), config);
  EXPECT_EQ(since.selected, std::vector<Kind>{Kind::kThrustLoss});
  EXPECT_NEAR(*since.fitted.parameter(Kind::kThrustLoss), 0.06, 0.005);
  EXPECT_NEAR(*gap::correctedEffects(since).parameter(Kind::kThrustLoss), worn.thrust_loss, 0.005);
  EXPECT_FALSE(since.motors.suspect_channel);
}

// Real vehicles fly their healthy flights with the same wiring, motors warming and air as any
// other: an effect those flights show alike is the vehicle's own and not named against them; a
// larger one since is. (The healthy flights' level is left out here: on these flights it would
// take up the wiring's drop before any effect is sought.)
TEST_F(SyntheticFlights, AnEffectTheHealthyFlightsShowAlikeIsNotNamed) {
  World wired;
  wired.supply_resistance = 0.04;
  const gap::Diagnosis alone = gap::diagnoseGap(model_, vehicle_, flights(wired), gap::DiagnosisConfig());
  EXPECT_EQ(alone.selected, std::vector<Kind>{Kind::kSupplyResistance});

  gap::DiagnosisConfig config;
  config.reference_effects = gap::fitReferenceEffects(model_, vehicle_, flights(wired, 1), config);
  ASSERT_EQ(config.reference_effects.count(Kind::kSupplyResistance), 1u);
  const gap::ReferenceEffect& healthy = config.reference_effects.at(Kind::kSupplyResistance);
  EXPECT_NEAR(healthy.value, 0.04, 0.01);
  EXPECT_GT(healthy.ci_half, 0.0);
  EXPECT_LT(healthy.signal_low, healthy.signal_high);  // the battery current it read there
  const gap::Diagnosis same = gap::diagnoseGap(model_, vehicle_, flights(wired), config);
  EXPECT_TRUE(same.selected.empty());
  const gap::EffectResult& wiring = same.effects.at(static_cast<std::size_t>(Kind::kSupplyResistance));
  EXPECT_EQ(wiring.reason.rfind("modelled as the vehicle's own, not named: no change from the vehicle's healthy flights", 0),
            0u)
      << wiring.reason;
  // Not named, but modelled: the correction carries it.
  EXPECT_EQ(same.background, std::vector<Kind>{Kind::kSupplyResistance});
  EXPECT_NEAR(same.fitted.parameter(Kind::kSupplyResistance).value_or(0.0), 0.04, 0.01);
  EXPECT_LT(same.heldout.after_rmse_pct, 0.5 * same.heldout.before_rmse_pct);
  EXPECT_NE(gap::gapReportYaml(same).find("background: [supply_resistance]"), std::string::npos);
  EXPECT_NE(gap::gapReportMarkdown(same, model_, "cmd").find("**Modelled, not named:** `supply_resistance`"),
            std::string::npos);

  World worse = wired;
  worse.supply_resistance = 0.12;
  const gap::Diagnosis since = gap::diagnoseGap(model_, vehicle_, flights(worse), config);
  EXPECT_EQ(since.selected, std::vector<Kind>{Kind::kSupplyResistance});
}

// ESCs 6 us off the bench's, within what healthy parts give (10 us): no finding, but modelled, so
// that what they explain is not left in the error a small effect must beat; the correction
// carries the offset.
TEST_F(SyntheticFlights, AnEffectWithinThePartsSpreadIsModelledUnnamed) {
  World parts;
  parts.esc_offset_us = 6.0;
  parts.no_current = true;
  const gap::Diagnosis alone = diagnose(parts);
  EXPECT_TRUE(alone.selected.empty()) << gap::gapReportMarkdown(alone, model_, "cmd");
  EXPECT_EQ(alone.background, std::vector<Kind>{Kind::kEscOffset});
  EXPECT_NEAR(alone.fitted.parameter(Kind::kEscOffset).value_or(0.0), 6.0, 1.5);
  EXPECT_LT(alone.heldout.after_rmse_pct, 0.5 * alone.heldout.before_rmse_pct);
  const std::string& reason = alone.effects.at(static_cast<std::size_t>(Kind::kEscOffset)).reason;
  EXPECT_EQ(reason.rfind("modelled as the vehicle's own, not named: changes the thrust by at most", 0), 0u) << reason;
  EXPECT_NE(gap::gapReportYaml(alone).find("background: [esc_offset]"), std::string::npos);
  EXPECT_NE(gap::gapReportMarkdown(alone, model_, "cmd").find("**Modelled, not named:** `esc_offset`"),
            std::string::npos);
}

TEST_F(SyntheticFlights, WithoutGeometryAWeakMotorIsNotNamedAsAnEffect) {
  World world;
  world.weak_motor = 2;
  world.weak_factor = 0.85;
  const gap::Diagnosis diagnosis =
      gap::diagnoseGap(model_, pe::Vehicle::upwardRotors(4), flights(world), gap::DiagnosisConfig());
  EXPECT_FALSE(diagnosis.motors.suspect_channel);
  // No balance was made: report.yaml names no basis for it.
  EXPECT_EQ(diagnosis.motors.basis, gap::MotorBasis::kNone);
  EXPECT_NE(gap::gapReportYaml(diagnosis).find("motor_basis: none\n"), std::string::npos);
  for (const gap::EffectResult& effect : diagnosis.effects) {
    EXPECT_TRUE(std::find(diagnosis.selected.begin(), diagnosis.selected.end(), effect.kind) == diagnosis.selected.end())
        << pe::effects::kindName(effect.kind) << ": " << effect.reason;
  }
  EXPECT_NE(std::find(diagnosis.problems.begin(), diagnosis.problems.end(),
                      "one motor may be at fault: channel 3's pulse width stands 59 us from the others' and, without "
                      "rotor geometry, a weak motor cannot be told from an effect: give the frame (--frame "
                      "quad_x|hexa_x|octo_x --arm-m) or --urdf; no effect is named"),
            diagnosis.problems.end())
      << testing::PrintToString(diagnosis.problems);
}

TEST_F(SyntheticFlights, WithOnePayloadAPropellerAt92PercentIsLocatedAgainstTheVehiclesReferenceOnly) {
  World healthy;
  healthy.one_mass_kg = 1.5;
  gap::DiagnosisConfig config;
  config.motor_reference = gap::learnReference(model_, vehicle_, flights(healthy), config);
  World weak = healthy;
  weak.weak_motor = 2;
  weak.weak_factor = 0.92;
  const gap::Diagnosis with = gap::diagnoseGap(model_, vehicle_, flights(weak), config);
  EXPECT_EQ(with.motors.basis, gap::MotorBasis::kReference);
  ASSERT_TRUE(with.motors.suspect_channel);
  EXPECT_EQ(*with.motors.suspect_channel, 3);
  EXPECT_TRUE(with.selected.empty());
  // Without it, 9 % is within the spread healthy vehicles show against the ideal balance.
  const gap::Diagnosis without = gap::diagnoseGap(model_, vehicle_, flights(weak), gap::DiagnosisConfig());
  EXPECT_EQ(without.motors.basis, gap::MotorBasis::kIdeal);
  EXPECT_FALSE(without.motors.suspect_channel);
}

// motor_healthy_gap_std (0.067, set on real healthy Crazyflies) holds from both sides: halved, the
// healthy real flights of test_real_flight_verdicts get a suspect (their largest gap is 0.103);
// raised by half (a suspect beyond 30 %), a propeller giving 75 % of its thrust (25 % short, the
// payloads' moments say) goes unnamed without a reference.
TEST_F(SyntheticFlights, WithoutAReferenceAPropellerAt75PercentIsNamed) {
  World world;
  world.weak_motor = 2;
  world.weak_factor = 0.75;
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, flights(world), gap::DiagnosisConfig());
  EXPECT_NE(diagnosis.motors.basis, gap::MotorBasis::kReference);
  std::string gaps = std::string(gap::motorBasisName(diagnosis.motors.basis)) + ":";
  for (const gap::MotorGap& motor : diagnosis.motors.motors) gaps += " " + std::to_string(motor.thrust_gap_pct) + "+-" + std::to_string(motor.ci_pct);
  ASSERT_TRUE(diagnosis.motors.suspect_channel) << gaps;
  EXPECT_EQ(*diagnosis.motors.suspect_channel, 3);
}

TEST_F(SyntheticFlights, WithAFrameByNameTheWeakMotorIsFound) {
  const pe::Vehicle frame = pe::Vehicle::frame("quad_x", 0.225);
  gap::DiagnosisConfig config;
  config.motor_reference = gap::learnReference(model_, frame, flights(World{}), config);
  World world;
  world.weak_motor = 2;
  world.weak_factor = 0.85;
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, frame, flights(world), config);
  ASSERT_TRUE(diagnosis.motors.suspect_channel);
  EXPECT_EQ(*diagnosis.motors.suspect_channel, 3);
  EXPECT_TRUE(diagnosis.selected.empty());
}

// The diagnosis' settings for a vehicle whose parts are known to be alike (no healthy spread): the
// payloads' moments then name any motor beyond min_gap, which these tests exercise.
gap::DiagnosisConfig partsAlike() {
  gap::DiagnosisConfig config;
  config.motor_healthy_gap_std = 0.0;
  return config;
}

// Steady hovers of a quad whose centre of gravity is 9 mm off the URDF's and whose motor `weak`
// gives 87 % of its modelled thrust: the thrusts that balance weight, roll, pitch and yaw, read
// back as the pulse widths the autopilot sent, with 0.2 % noise on each block. Drag torque is proportional to the thrust that
// flies, but for a worn propeller (`keeps_torque`), whose torque is the intact one's at its speed.
std::vector<gap::Block> hoversWithAWeakMotor(const pe::Vehicle& vehicle, int weak,
                                             const std::function<double(double, double)>& pwm_for,
                                             bool keeps_torque = false, double factor = 0.87) {
  const Eigen::Vector2d empty_cg(0.008, -0.005);
  const double empty_kg = 1.3;
  // Each block's mean thrust as read through 0.2 % noise: exact moments would give the jackknife
  // nothing to vary and the gap no interval.
  std::mt19937 rng(static_cast<unsigned>(weak + 7));
  std::normal_distribution<double> noise(0.0, 0.002);
  std::vector<gap::Block> blocks;
  int group = 0;
  for (double payload_kg : {0.0, 0.15, 0.25}) {
    const double mass = empty_kg + payload_kg;
    const Eigen::Vector2d cg = empty_kg * empty_cg / mass;  // the payload hangs below the origin
    Eigen::Matrix4d a;
    Eigen::Vector4d b(mass * pe::kStandardGravity, 0.0, 0.0, 0.0);
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d arm = vehicle.rotors[k].position_m.head<2>() - cg;
      const double torque_per_thrust = keeps_torque && k == weak ? 1.0 / factor : 1.0;
      a.col(k) << 1.0, arm.x(), arm.y(), vehicle.rotors[k].spin_direction * torque_per_thrust;
    }
    const Eigen::Vector4d thrust = a.colPivHouseholderQr().solve(b);
    for (int i = 0; i < 30; ++i, ++group) {
      gap::Block block;
      block.segment = static_cast<int>(payload_kg * 100);
      block.group = group;
      block.mass_kg = mass;
      block.voltage_v = 12.0;
      block.hover = true;
      block.truth_n = mass * pe::kStandardGravity;
      for (int k = 0; k < 4; ++k) {
        block.pwm_us[k] = pwm_for(thrust[k] / (k == weak ? factor : 1.0) * (1.0 + noise(rng)), block.voltage_v);
        block.axis_up[k] = 1.0;
      }
      blocks.push_back(block);
    }
  }
  return blocks;
}

TEST_F(SyntheticFlights, TheMotorBalanceFindsTheWeakMotorWhicheverItIsDespiteAnOffCentreCog) {
  for (int weak = 0; weak < 4; ++weak) {
    const std::vector<gap::Block> blocks =
        hoversWithAWeakMotor(vehicle_, weak, [&](double thrust, double voltage) { return pwmFor(thrust, voltage); });
    const gap::MotorBalance balance = gap::balanceMotors(views_, vehicle_, blocks, {1, 2, 3, 4}, partsAlike());
    ASSERT_TRUE(balance.suspect_channel) << "weak motor " << weak + 1;
    // A vehicle whose parts spread as healthy ones do: 13 % is within three times that spread.
    EXPECT_FALSE(gap::balanceMotors(views_, vehicle_, blocks, {1, 2, 3, 4}, gap::DiagnosisConfig()).suspect_channel);
    EXPECT_EQ(*balance.suspect_channel, weak + 1);
    EXPECT_NEAR(balance.motors[weak].thrust_gap_pct, 13.0, 0.5);
  }
}

TEST_F(SyntheticFlights, TheMotorBalanceFindsAWornPropellerThatLeavesTheYawBalanceAsItWas) {
  // Its torque is what its speed gives an intact one: the model's yaw balance holds, and only the
  // moments across the payloads show it.
  for (int weak = 0; weak < 4; ++weak) {
    const std::vector<gap::Block> blocks = hoversWithAWeakMotor(
        vehicle_, weak, [&](double thrust, double voltage) { return pwmFor(thrust, voltage); }, true);
    const gap::MotorBalance balance = gap::balanceMotors(views_, vehicle_, blocks, {1, 2, 3, 4}, partsAlike());
    ASSERT_TRUE(balance.suspect_channel) << "worn propeller on motor " << weak + 1;
    EXPECT_EQ(*balance.suspect_channel, weak + 1);
    EXPECT_NEAR(balance.motors[weak].thrust_gap_pct, 13.0, 0.5);
  }
}

TEST_F(SyntheticFlights, AMomentFitRestingOnItsBoundNamesNoMotor) {
  // A propeller at 60 % needs a gap of 67 %, beyond the search's 35 %: the fit rests on its bound.
  const std::vector<gap::Block> blocks = hoversWithAWeakMotor(
      vehicle_, 1, [&](double thrust, double voltage) { return pwmFor(thrust, voltage); }, false, 0.6);
  const gap::MotorBalance balance = gap::balanceMotors(views_, vehicle_, blocks, {1, 2, 3, 4}, partsAlike());
  EXPECT_EQ(balance.basis, gap::MotorBasis::kPayloads);
  EXPECT_FALSE(balance.suspect_channel) << "channel " << *balance.suspect_channel;
}

TEST_F(SyntheticFlights, TheMotorBalanceNamesNoMotorForAnOffCentreCogAlone) {
  std::vector<gap::Block> blocks =
      hoversWithAWeakMotor(vehicle_, -1, [&](double thrust, double voltage) { return pwmFor(thrust, voltage); });
  const gap::MotorBalance balance = gap::balanceMotors(views_, vehicle_, blocks, {1, 2, 3, 4}, gap::DiagnosisConfig());
  EXPECT_FALSE(balance.suspect_channel);
  EXPECT_NEAR(balance.cg_offset_x_m, 0.008 * 1.3 / (1.3 + 0.4 / 3.0), 0.001);
}

TEST_F(SyntheticFlights, DropsASegmentsLastBlockWhenItSpansLessThanHalfABlock) {
  pe::Flight flight = fly("f1.bag", World{}, {1.3}, 12.0, 1);
  gap::BlockConfig config;
  config.block_s = 1.0;
  const double start = flight.segments[0].start_s;
  flight.segments[0].end_s = start + 10.1;  // ten whole blocks and 0.1 s of an eleventh
  EXPECT_EQ(gap::cutIntoBlocks(flight, 0, vehicle_, config, 0).blocks.size(), 10u);
  flight.segments[0].end_s = start + 10.6;  // the eleventh spans more than half a block: kept
  EXPECT_EQ(gap::cutIntoBlocks(flight, 0, vehicle_, config, 0).blocks.size(), 11u);
}

TEST_F(SyntheticFlights, ReportsWhatItCannotUseAndDiagnosesTheRest) {
  std::vector<pe::Flight> all = flights(World{});
  all[1].segments.push_back({1000.0, 1010.0, 1.4});
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, all, gap::DiagnosisConfig{});
  ASSERT_EQ(diagnosis.problems.size(), 1u);
  EXPECT_EQ(diagnosis.problems[0], "f2.bag: segment 4 (1000-1010 s) lies outside the log's rc/out span 0.00-135.98 s; skipped");
  EXPECT_GT(diagnosis.overall.samples, 500);
}

TEST_F(SyntheticFlights, RefusesWhenNothingIsUsable) {
  std::vector<pe::Flight> all = flights(World{});
  for (pe::Flight& flight : all) flight.segments = {{5000.0, 5010.0, 1.4}};
  try {
    gap::diagnoseGap(model_, vehicle_, all, gap::DiagnosisConfig{});
    FAIL() << "diagnosed flights with nothing usable";
  } catch (const pe::DataError& e) {
    // The refusal is the only line the user sees: it carries each segment's problem.
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("no usable sample in any weighed segment of any flight: f1.bag: segment 1 (5000-5010 s) lies "
                         "outside the log's rc/out span 0.00-",
                         0),
              0u)
        << what;
    EXPECT_NE(what.find(" s; f2.bag: segment 1 (5000-5010 s) lies outside the log's rc/out span 0.00-"), std::string::npos)
        << what;
  }
}

TEST_F(SyntheticFlights, SaysWhyNothingIsUsableWithTheNumbers) {
  World world;
  world.kicks = true;
  gap::DiagnosisConfig config;
  config.max_pwm_change_us = 1.0;  // nothing this flight does is that steady
  config.rotor_time_constant_s = 0.0;
  try {
    gap::diagnoseGap(model_, vehicle_, flights(world), config);
    FAIL() << "diagnosed flights with nothing steady";
  } catch (const pe::DataError& e) {
    EXPECT_STREQ(e.what(), "no usable sample in any weighed segment of any flight: 585 blocks transient (collective "
                           "PWM changing by more than 1 us or accelerating faster than 0.8 m/s^2 vertically within 1 s)");
  }
}

// A model of another battery than the vehicle's (a 4-cell vehicle against a 3-cell model): said,
// with both ranges.
TEST_F(SyntheticFlights, SaysWhenTheFlightsLieOutsideTheModelsDomain) {
  std::vector<pe::Flight> all = flights(World{});
  for (pe::Flight& flight : all) {
    for (pe::BatteryReading& reading : flight.streams.battery) reading.voltage_v += 4.0;
  }
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, all, gap::DiagnosisConfig{});
  const std::string outside =
      "585 of 585 blocks lie outside the model's domain: the flights' battery reads 15.03-16.40 V and their pulse "
      "widths 1621-1788 us, the model covers 10.50-12.60 V and 1200-1900 us (outside: clamp): is this the right "
      "model for this vehicle and battery?";
  // Looked up, not taken as the last problem: the flights' implausible thrust is said after it.
  EXPECT_NE(std::find(diagnosis.problems.begin(), diagnosis.problems.end(), outside), diagnosis.problems.end());
}

TEST_F(SyntheticFlights, ReportYamlHoldsTheContract) {
  World world;
  world.thrust_loss = 0.06;
  const std::string yaml = gap::gapReportYaml(diagnose(world));
  for (const char* key : {"gap:", "bias_pct:", "rmse_pct:", "payload_err_pct:", "where:", "motors:", "suspect_motor:",
                          "effects:", "selected: [thrust_loss]", "heldout:", "before_rmse_pct:", "after_rmse_pct:",
                          "before_payload_err_pct:", "after_payload_err_pct:"}) {
    EXPECT_NE(yaml.find(key), std::string::npos) << key;
  }
}

// Hovers at one mass and one battery charge, no current sensor: a thrust loss and an ESC offset
// lower the thrust alike at every block, and nothing in these flights can tell them apart.
TEST_F(SyntheticFlights, ReportsAmbiguousWhenTheFlightsCannotSeparateTwoEffects) {
  World world;
  world.thrust_loss = 0.05;
  std::vector<pe::Flight> all;
  for (unsigned f = 1; f <= 5; ++f) {
    all.push_back(fly("f" + std::to_string(f) + ".bag", world, {1.5, 1.5}, 12.0, f));
    for (pe::BatteryReading& reading : all.back().streams.battery) reading.current_a = std::nan("");
  }
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, all, gap::DiagnosisConfig{});
  EXPECT_TRUE(diagnosis.selected.empty()) << testing::PrintToString(diagnosis.selected);
  ASSERT_EQ(diagnosis.ambiguous.size(), 1u);
  const std::vector<Kind>& group = diagnosis.ambiguous[0].kinds;
  EXPECT_EQ(std::set<Kind>(group.begin(), group.end()), (std::set<Kind>{Kind::kThrustLoss, Kind::kEscOffset}));
  EXPECT_GT(diagnosis.ambiguous[0].swap_p_value, 0.05);
  EXPECT_NE(diagnosis.ambiguous[0].separating_flight.find("hover with two payloads"), std::string::npos);
  // The correction still uses the group's leader: the gap shrinks whatever the name.
  EXPECT_TRUE(diagnosis.fitted.parameter(group[0]));
  EXPECT_LT(diagnosis.heldout.after_rmse_pct, 0.5 * diagnosis.heldout.before_rmse_pct);
  const std::string yaml = gap::gapReportYaml(diagnosis);
  EXPECT_NE(yaml.find("selected: []"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("ambiguous:\n  - [" + std::string(pe::effects::kindName(group[0])) + ", " +
                      pe::effects::kindName(group[1]) + "]"),
            std::string::npos)
      << yaml;
  const std::string md = gap::gapReportMarkdown(diagnosis, model_, "cmd");
  EXPECT_NE(md.find("**Ambiguous: one of"), std::string::npos);
  for (const gap::EffectResult& effect : diagnosis.effects) {
    if (group.end() != std::find(group.begin(), group.end(), effect.kind)) {
      EXPECT_EQ(effect.reason.rfind("ambiguous: ", 0), 0u) << effect.reason;
    }
  }
}

// Issue 33 point 5: a motor heating too small to move the thrust beyond healthy parts' spread
// (0.2 %/C over the day's 14-26 C: at most 1.6 %) is named alone by its shape, which no part
// gives; after a thrust loss it is not, since what a mis-shaped law of the first effect leaves
// over has such a shape too (the family's development seeds: motor heating and the day's air
// named beside supply resistances, ESC offsets and thrust losses that were not of their law).
TEST_F(SyntheticFlights, AfterAFirstEffectASecondMustMoveTheThrustBeyondThePartsSpread) {
  World warm;
  warm.motor_temperature = true;
  warm.motor_per_c = -0.002;
  warm.no_current = true;
  const gap::Diagnosis alone = diagnose(warm);
  ASSERT_EQ(alone.selected, std::vector<Kind>{Kind::kMotorTemperature});
  const gap::EffectResult& heating = alone.effects.at(static_cast<std::size_t>(Kind::kMotorTemperature));
  EXPECT_EQ(heating.size.blocks_beyond, 0);
  EXPECT_LE(heating.size.imitated_share, gap::PartsSpread().max_imitated_share);

  World both = warm;
  both.thrust_loss = 0.06;
  both.telemetry = true;  // without the current, the RPM view tells the loss from an ESC offset
  const gap::Diagnosis after = diagnose(both);
  EXPECT_EQ(after.selected, std::vector<Kind>{Kind::kThrustLoss}) << gap::gapReportMarkdown(after, model_, "cmd");
  const std::string& reason = after.effects.at(static_cast<std::size_t>(Kind::kMotorTemperature)).reason;
  EXPECT_EQ(reason.rfind("not named: after thrust_loss, an effect must move the thrust beyond healthy parts' spread", 0),
            0u)
      << reason;
}

// A suspect motor's factor is a law as well, and a mis-shaped one (a chipped blade also turns less
// drag torque, and its thrust lost changes with the operating point): beside it an effect is named
// by its size alone, as after a first effect. The heating named alone above, with propeller 3 at
// 85 % of its thrust: the motor located, the heating's shape not named.
TEST_F(SyntheticFlights, BesideASuspectMotorAnEffectMustMoveTheThrustBeyondThePartsSpread) {
  World warm;
  warm.motor_temperature = true;
  warm.motor_per_c = -0.002;
  warm.no_current = true;
  World healthy = warm;
  healthy.motor_per_c = 0.0;
  gap::DiagnosisConfig config;
  config.motor_reference = gap::learnReference(model_, vehicle_, flights(healthy, 1), config);
  warm.weak_motor = 2;
  warm.weak_factor = 0.85;
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, flights(warm), config);
  ASSERT_TRUE(diagnosis.motors.suspect_channel);
  EXPECT_EQ(*diagnosis.motors.suspect_channel, 3);
  EXPECT_TRUE(diagnosis.selected.empty()) << gap::gapReportMarkdown(diagnosis, model_, "cmd");
  const std::string& reason = diagnosis.effects.at(static_cast<std::size_t>(Kind::kMotorTemperature)).reason;
  EXPECT_EQ(reason.rfind("not named: after the suspect motor's factor, an effect must move the thrust beyond healthy "
                         "parts' spread", 0),
            0u)
      << reason;
}

// One rotor a few per cent weak, below the suspect's threshold, lacks a share of the vehicle's
// thrust that a thrust loss on every rotor takes up as well; the moment balance shows which: the
// candidate is tried on top of that motor's factor and not named (issue 33 point 4). Propeller 3
// at 96 % of its thrust against the vehicle's healthy flights, parts taken to spread by 0.2 % (the
// vehicle's 1 % loss beyond them) and no current logged (this world's follows the command, and the
// current view would tell the two apart).
TEST_F(SyntheticFlights, AWeakRotorBelowTheSuspectsThresholdIsNotNamedAThrustLoss) {
  World world;
  world.no_current = true;
  gap::DiagnosisConfig config;
  config.parts_spread.thrust_fraction = 0.002;
  config.motor_reference = gap::learnReference(model_, vehicle_, flights(world, 1), config);
  world.weak_motor = 2;
  world.weak_factor = 0.96;
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, flights(world), config);
  EXPECT_FALSE(diagnosis.motors.suspect_channel);
  EXPECT_TRUE(diagnosis.selected.empty()) << gap::gapReportMarkdown(diagnosis, model_, "cmd");
  // Its first try, before an ESC offset within the parts' spread is modelled as the vehicle's own.
  const auto first = std::find_if(diagnosis.trace.begin(), diagnosis.trace.end(),
                                  [](const gap::SelectionStep& step) { return step.kind == Kind::kThrustLoss; });
  ASSERT_NE(first, diagnosis.trace.end());
  EXPECT_EQ(first->verdict.rfind("not named: one motor explains it: channel 3 lacks", 0), 0u) << first->verdict;
}

// A healthy flight's blocks err together (its payload's hang, its air): an effect read from a
// signal that changes between flights, as the motors' temperature on three days, is known only as
// well as three flights tell it, and the reference's interval says so: the flights' jackknife,
// used only where the signal changes mostly between flights (more than half its variance between
// the flights' means). Three healthy flights at 17, 20 and 23 C (6 C^2 between them), each
// 0.6-1 % off on its own, not warming, warming by 6 C (3 C^2 within: 0.67 between) or by 12 C
// (12 C^2 within: 0.33 between).
TEST_F(SyntheticFlights, AReferenceEffectReadBetweenFlightsIsKnownAsWellAsItsFlightsTellIt) {
  World warm;
  warm.motor_temperature = true;
  warm.motor_per_c = -0.002;
  warm.flight_spread = 0.01;
  warm.no_current = true;
  const auto reference = [&](double warming_c) {
    warm.motor_warming_c = warming_c;
    const std::vector<pe::Flight> all = flights(warm);
    const std::vector<pe::Flight> three(all.begin(), all.begin() + 3);
    const gap::ReferenceEffects effects = gap::fitReferenceEffects(model_, vehicle_, three, gap::DiagnosisConfig());
    EXPECT_EQ(effects.count(Kind::kMotorTemperature), 1u);
    return effects.count(Kind::kMotorTemperature) ? effects.at(Kind::kMotorTemperature) : gap::ReferenceEffect{};
  };
  // Measured: +-0.016 and +-0.0105 per C (the jackknife of three flights) still and warming 6 C;
  // +-0.0007 (the fit's) warming 12 C.
  const gap::ReferenceEffect still = reference(0.0);
  EXPECT_GT(still.ci_half, 0.005);
  EXPECT_LT(std::abs(still.value - warm.motor_per_c), still.ci_half);
  EXPECT_GT(reference(6.0).ci_half, 0.005);
  EXPECT_LT(reference(12.0).ci_half, 0.002);
}

// The healthy flights' effects are read on the blocks the selection reads a candidate on, the
// steady ones: a transient block also carries what the lag model leaves over, which widens the
// reference's interval and shifts its value until a change no longer stands out from it. A 4 %
// thrust loss on healthy flights whose autopilot kicks the PWM up by 150 us every 10 s, the
// vehicle lifting 0.1 s later (a pure delay, which the identified first-order lag of 0.11 s
// leaves 31 % of): read as without the kicks, 0.0401 +- 0.0010. (On every block it was 0.0389 +-
// 0.0014.)
TEST_F(SyntheticFlights, AReferenceIsReadOnTheSteadyBlocksAsTheSelectionReadsAnEffect) {
  World world;
  world.thrust_loss = 0.04;
  world.kick_lift_delay_s = 0.1;
  world.kick_us = 150.0;
  const gap::ReferenceEffect still =
      gap::fitReferenceEffects(model_, vehicle_, flights(world), gap::DiagnosisConfig()).at(Kind::kThrustLoss);
  world.kicks = true;
  const gap::ReferenceEffect kicked =
      gap::fitReferenceEffects(model_, vehicle_, flights(world), gap::DiagnosisConfig()).at(Kind::kThrustLoss);
  EXPECT_NEAR(still.value, 0.04, 0.001);
  EXPECT_NEAR(kicked.value, still.value, 0.0005);
  EXPECT_LT(kicked.ci_half, 1.15 * still.ci_half);
}

// The healthy flights' thrust level holds their motors' warmth: the warming is then read as a
// change from that warmth, not from the bench's 22 C, which would count the healthy flights'
// warmth twice (once in the level, once in the effect) and bend the fitted law to take up the
// difference. Motors warming 14 C over each flight, losing 0.3 %/C: the healthy flights' motors
// average 27 C, their level 1.4 % below the bench's.
TEST_F(SyntheticFlights, AgainstHealthyFlightsTheMotorsWarmingIsReadFromTheirWarmth) {
  World warm;
  warm.motor_temperature = true;
  warm.motor_per_c = -0.003;
  warm.motor_warming_c = 14.0;
  warm.warming_heats = true;
  warm.no_current = true;
  gap::DiagnosisConfig config;
  config.motor_reference = gap::learnReference(model_, vehicle_, flights(warm, 1), config);
  const double healthy_c = config.motor_reference->motor_temperature_c;
  EXPECT_GT(healthy_c, 22.0);  // the days' 14-26 C and the warming's 0-14 C
  EXPECT_LT(healthy_c, 40.0);
  EXPECT_TRUE(std::isnan(config.motor_reference->air_density_kg_m3));  // no air logged
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, flights(warm), config);
  EXPECT_EQ(diagnosis.fitted.motor_reference_c, healthy_c);
  const gap::EffectResult& heating = diagnosis.effects.at(static_cast<std::size_t>(Kind::kMotorTemperature));
  EXPECT_NEAR(heating.parameter, warm.motor_per_c, 0.0003) << heating.reason;
  EXPECT_EQ(diagnosis.selected, std::vector<Kind>{Kind::kMotorTemperature});
  // Read from the bench's 22 C, the level's 1.4 % needed another effect modelled beside (measured).
  EXPECT_TRUE(diagnosis.background.empty()) << testing::PrintToString(diagnosis.background);
}

// A second effect that is there, and large, is still named beside the first.
TEST_F(SyntheticFlights, ASecondEffectBeyondWhatTheFirstLawLeavesIsNamed) {
  World world;
  world.thrust_loss = 0.05;
  world.supply_resistance = 0.08;
  const gap::Diagnosis diagnosis = diagnose(world);
  EXPECT_EQ(std::set<Kind>(diagnosis.selected.begin(), diagnosis.selected.end()),
            (std::set<Kind>{Kind::kThrustLoss, Kind::kSupplyResistance}));
}

TEST_F(SyntheticFlights, TheNestedHoldOutScoresEachFlightOnADiagnosisThatNeverSawIt) {
  World world;
  world.thrust_loss = 0.06;
  const gap::Diagnosis diagnosis = diagnose(world);
  const gap::NestedHoldOut& nested = diagnosis.heldout.nested;
  ASSERT_TRUE(nested.unavailable.empty()) << nested.unavailable;
  ASSERT_EQ(nested.folds.size(), 3u);
  std::multiset<std::string> scored;
  for (const gap::NestedFold& fold : nested.folds) {
    for (const std::string& name : fold.scored_on) {
      scored.insert(name);
      EXPECT_EQ(std::count(fold.fitted_on.begin(), fold.fitted_on.end(), name), 0) << name;
    }
    EXPECT_EQ(fold.fitted_on.size() + fold.scored_on.size(), 5u);
    EXPECT_EQ(fold.effects, std::vector<Kind>{Kind::kThrustLoss});
  }
  EXPECT_EQ(scored, (std::multiset<std::string>{"f1.bag", "f2.bag", "f3.bag", "f4.bag", "f5.bag"}));
  EXPECT_GT(nested.before_rmse_pct, 5.0);
  EXPECT_LT(nested.after_rmse_pct, 0.3 * nested.before_rmse_pct);
  EXPECT_NE(gap::gapReportYaml(diagnosis).find("nested:"), std::string::npos);
}

TEST_F(SyntheticFlights, TheNestedHoldOutNeedsThreeUnits) {
  std::vector<pe::Flight> two = flights(World{});
  two.resize(2);
  for (pe::Flight& flight : two) flight.segments.resize(1);
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, two, gap::DiagnosisConfig{});
  EXPECT_EQ(diagnosis.heldout.nested.unavailable, "needs three flights or more (2): the inner selection must hold one out too");
}

// Every candidate gets one line, and its verdict agrees with the numbers beside it: p tests the
// joint held-out error, so p = 1 exactly when that error does not fall.
TEST_F(SyntheticFlights, EachCandidateHasOneLineWhoseTestsAgreeWithItsErrors) {
  World world;
  world.supply_resistance = 0.08;
  const gap::Diagnosis diagnosis = diagnose(world);
  const gap::DiagnosisConfig config;
  ASSERT_EQ(diagnosis.effects.size(), pe::effects::kAllKinds.size());
  const std::string md = gap::gapReportMarkdown(diagnosis, model_, "cmd");
  for (const gap::EffectResult& effect : diagnosis.effects) {
    const std::string name = pe::effects::kindName(effect.kind);
    EXPECT_FALSE(effect.reason.empty()) << name;
    std::size_t rows = 0;
    for (std::size_t at = md.find("\n| " + name + " | "); at != std::string::npos;
         at = md.find("\n| " + name + " | ", at + 1)) {
      ++rows;
    }
    EXPECT_EQ(rows, 1u) << name;
    const bool selected =
        std::find(diagnosis.selected.begin(), diagnosis.selected.end(), effect.kind) != diagnosis.selected.end();
    EXPECT_EQ(effect.reason.rfind("selected in round", 0) == 0, selected) << name << ": " << effect.reason;
    if (!effect.testable || effect.base_joint_rmse_pct == 0.0) continue;
    EXPECT_EQ(effect.p_value > 0.999, effect.joint_rmse_pct >= effect.base_joint_rmse_pct)
        << name << ": " << effect.reason;
    if (effect.reason.find("not significant") != std::string::npos) {
      EXPECT_GE(effect.p_value, config.significance) << name << ": " << effect.reason;
    }
  }
  for (const gap::SelectionStep& step : diagnosis.trace) {
    EXPECT_FALSE(step.verdict.empty());
    if (step.verdict.find("p = 1.000") != std::string::npos) {
      EXPECT_EQ(step.verdict.find("not significant"), std::string::npos) << step.verdict;
    }
  }
}

// issue 35: gap_samples.csv's views stand on one footing, the plain model's: the weak motor's
// factor the balance finds is in the corrected column only. A weak propeller turns at the speed
// its command asks and lifts less: both views read high by its missing share, alike.
TEST_F(SyntheticFlights, TheSamplesViewsAreThePlainModelsEvenWithASuspectMotor) {
  World healthy;
  healthy.telemetry = true;
  gap::DiagnosisConfig config;
  config.motor_reference = gap::learnReference(model_, vehicle_, flights(healthy), config);
  World world = healthy;
  world.weak_motor = 2;
  world.weak_factor = 0.85;
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, flights(world), config);
  ASSERT_TRUE(diagnosis.motors.suspect_channel);
  double rpm = 0.0, pwm = 0.0;
  int n = 0;
  for (const gap::GapSample& s : diagnosis.samples) {
    if (!std::isfinite(s.rpm_view_n)) continue;
    rpm += s.rpm_view_n / s.truth_n;
    pwm += s.model_n / s.truth_n;
    ++n;
  }
  ASSERT_GT(n, 50);
  EXPECT_GT(pwm / n, 1.02);
  EXPECT_NEAR(rpm / n, pwm / n, 0.005);
}

// issue 35: the diagnosis and the node agree on every sample outside the domain. Two flights on a
// pack sagged below the bench's lowest voltage (10.5 V), where the node clamps, and one inside:
// every sample's model thrust in the diagnosis is what the node estimated over the block's frames,
// as closely outside the domain as inside it, where the surfaces' own values are 1 % off. (Inside
// and out they differ by 0.13 %: the replay hands the node whole microseconds, as RCOut carries
// them, truncating these flights' fractional ones by 0.5 us on average.)
TEST_F(SyntheticFlights, TheDiagnosisAndTheNodeAgreeOnEverySampleOutsideTheDomain) {
  const std::vector<pe::Flight> all = {fly("in.bag", World{}, {1.3, 1.6, 1.75}, 12.0, 1),
                                       fly("low1.bag", World{}, {1.35, 1.5, 1.8}, 10.0, 2),
                                       fly("low2.bag", World{}, {1.45, 1.65, 1.4}, 9.8, 3)};
  const gap::DiagnosisConfig config;
  const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, all, config);
  pe::offline::EstimateOptions options;
  options.estimator = pe::offline::replayEstimatorConfig(vehicle_);
  options.sample_rate_hz = 0.0;
  std::vector<pe::offline::FlightEstimate> node;
  for (const pe::Flight& flight : all) node.push_back(pe::offline::estimateFlight(model_, vehicle_, flight.streams, options));
  // Mean relative differences from the diagnosis' model thrust, inside and outside the domain.
  std::array<double, 2> node_off{}, surfaces_off{};
  std::array<int, 2> compared{};
  for (const gap::GapSample& sample : diagnosis.samples) {
    const int outside = sample.flight == 0 ? 0 : 1;
    ASSERT_EQ(outside == 1, sample.voltage_v < model_.domain().voltage_min_v) << sample.voltage_v << " V";
    double sum_n = 0.0;
    int frames = 0;
    for (const pe::offline::EstimateSample& estimate : node[sample.flight].samples) {
      if (std::abs(estimate.time_s - sample.time_s) >= 0.5 * config.block_s) continue;
      EXPECT_EQ(estimate.motors_out_of_domain, 4 * outside);
      sum_n += estimate.thrust_n;
      ++frames;
    }
    ASSERT_GE(frames, 40);
    EXPECT_NEAR(sample.model_n, sum_n / frames, 4e-3 * sample.model_n) << sample.flight << " at " << sample.time_s << " s";
    node_off[outside] += std::abs(sum_n / frames / sample.model_n - 1.0);
    surfaces_off[outside] += std::abs(4.0 * views_.surfaceThrust(sample.pwm_us, sample.voltage_v) / sample.model_n - 1.0);
    ++compared[outside];
  }
  ASSERT_GT(compared[0], 80);
  ASSERT_GT(compared[1], 160);
  for (int i = 0; i < 2; ++i) {
    node_off[i] /= compared[i];
    surfaces_off[i] /= compared[i];
  }
  // Measured: 0.14 % inside and 0.13 % outside; the surfaces 1.0 % outside.
  EXPECT_LT(node_off[1], 1.2 * node_off[0]);
  EXPECT_GT(surfaces_off[1], 5.0 * node_off[1]) << "the surfaces' own values would have disagreed";
}

// issue 35: a model whose policy is reject gives the node nothing outside its domain; the diagnosis
// leaves out the same blocks and says so, with the count.
TEST_F(SyntheticFlights, LeavesOutWhatAModelThatRejectsWouldRefuse) {
  const pe::PropulsionModel rejecting = withOutsidePolicy(model_, pe::OutsideDomain::kReject);
  const std::vector<pe::Flight> sagged = {fly("low1.bag", World{}, {1.3, 1.6, 1.75}, 10.3, 1),
                                          fly("low2.bag", World{}, {1.35, 1.5, 1.8}, 10.2, 2)};
  const gap::Diagnosis clamped = gap::diagnoseGap(model_, vehicle_, sagged, gap::DiagnosisConfig{});
  try {
    gap::diagnoseGap(rejecting, vehicle_, sagged, gap::DiagnosisConfig{});
    FAIL() << "diagnosed flights that the model rejects";
  } catch (const pe::DataError& e) {
    EXPECT_EQ(std::string(e.what()), "no usable sample in any weighed segment of any flight: " +
                                         std::to_string(clamped.blocks + clamped.transient_blocks) +
                                         " blocks outside the model's domain, which it rejects (outside: reject) as "
                                         "the node would");
  }
  // Flights partly inside: the rest is diagnosed, and the line says what was left out.
  std::vector<pe::Flight> mixed = sagged;
  mixed.push_back(fly("f1.bag", World{}, {1.3, 1.6, 1.75}, 12.4, 3));
  mixed.push_back(fly("f2.bag", World{}, {1.35, 1.5, 1.8}, 11.8, 4));
  const gap::Diagnosis partly = gap::diagnoseGap(rejecting, vehicle_, mixed, gap::DiagnosisConfig{});
  EXPECT_EQ(std::count(partly.problems.begin(), partly.problems.end(),
                       std::to_string(clamped.blocks + clamped.transient_blocks) +
                           " blocks outside the model's domain left out: it rejects them (outside: reject), as the "
                           "node does"),
            1);
  for (const gap::GapSample& sample : partly.samples) EXPECT_GE(sample.voltage_v, model_.domain().voltage_min_v);
}

// issue 36: the avionics' draw is measured where the log shows it, the battery current on the
// ground with every motor stopped, and taken out of the current view, whatever its size (2.5 A
// here; the fit alone is bounded at 3 A). Each flight gets 4 s on the ground, disarmed at 900 us,
// before its first hover.
TEST_F(SyntheticFlights, TheCurrentViewTakesOutTheDrawMeasuredOnTheGround) {
  World world;
  world.avionics_a = 2.5;
  std::vector<pe::Flight> all = flights(world);
  for (pe::Flight& flight : all) {
    std::vector<pe::RcOutFrame> ground;
    std::vector<pe::BatteryReading> battery;
    for (int i = -200; i < 0; ++i) {
      pe::RcOutFrame frame;
      frame.time_s = i * 0.02;
      for (int k = 0; k < 4; ++k) frame.pwm_us[k] = 900.0;
      ground.push_back(frame);
      if (i % 5 == 0) battery.push_back({frame.time_s, flight.streams.battery.front().voltage_v, -2.5});
    }
    flight.streams.rc_out.insert(flight.streams.rc_out.begin(), ground.begin(), ground.end());
    flight.streams.battery.insert(flight.streams.battery.begin(), battery.begin(), battery.end());
  }
  const auto current_view_level = [](const gap::Diagnosis& diagnosis) {
    double sum = 0.0;
    int n = 0;
    for (const gap::GapSample& s : diagnosis.samples) {
      if (!std::isfinite(s.current_view_n)) continue;
      sum += s.current_view_n / s.truth_n;
      ++n;
    }
    return sum / n;
  };
  const gap::Diagnosis measured = gap::diagnoseGap(model_, vehicle_, all, gap::DiagnosisConfig{});
  EXPECT_NE(measured.ground_draw.find("every motor stopped: 2.50 A on f1.bag, 2.50 A on f2.bag"), std::string::npos)
      << measured.ground_draw;
  EXPECT_NEAR(current_view_level(measured), 1.0, 0.005);
  const gap::Diagnosis fitted = gap::diagnoseGap(model_, vehicle_, flights(world), gap::DiagnosisConfig{});
  EXPECT_EQ(fitted.ground_draw,
            "the current view takes out the avionics' draw fitted per held-out unit within 0-3 A (no flight has at "
            "least 5 battery readings with every motor stopped (at or below 1000 us) for a second)");
  EXPECT_GT(current_view_level(fitted), 1.02) << "the samples' current view holds the avionics where nothing measured it";
  // gap_samples.csv's current is the battery's either way.
  ASSERT_EQ(measured.samples.size(), fitted.samples.size());
  EXPECT_NEAR(measured.samples[0].current_a, fitted.samples[0].current_a, 1e-9);
  EXPECT_TRUE(measured.selected.empty());
}

// Motors warming 16 C over each flight and losing 0.3 %/C of their thrust to it, their logged
// temperature starting at each day's (14-26 C), which the thrust does not follow: the heating's law
// also reads the days' temperatures and errs between flights. Over all blocks a thrust loss within
// the parts' spread (the vehicle's own, not nameable) explains more than the heating, which passes
// every test; within each flight only the heating explains anything. Modelling the thrust loss first
// left the heating not significant and named an ESC offset (the family's motor heatings beside the
// day's air, development seed 5151): the vehicle's own is not modelled first where the candidate
// that passes explains the error within flights better, and joins the correction after.
TEST_F(SyntheticFlights, AHeatingExplainingTheErrorWithinFlightsIsNotHiddenByTheVehiclesOwnEffect) {
  World world;
  world.motor_temperature = true;
  world.motor_warming_c = 16.0;
  world.warming_heats = true;
  world.day_heats = false;
  world.motor_per_c = -0.003;
  world.no_current = true;
  const gap::Diagnosis diagnosis = diagnose(world);
  const std::string report = gap::gapReportMarkdown(diagnosis, model_, "cmd");
  const auto first_round = [&](Kind kind) {
    for (const gap::SelectionStep& step : diagnosis.trace) {
      if (step.round == 1 && step.kind == kind) return step;
    }
    return gap::SelectionStep{};
  };
  // The premise: the heating passes, and the thrust loss, not nameable, explains more.
  const gap::SelectionStep heating = first_round(Kind::kMotorTemperature), loss = first_round(Kind::kThrustLoss);
  EXPECT_EQ(heating.verdict, "passes every test") << report;
  EXPECT_EQ(loss.verdict.rfind("not named: changes the thrust by at most", 0), 0u) << report;
  EXPECT_LT(loss.joint_rmse_pct, heating.joint_rmse_pct) << report;
  EXPECT_EQ(diagnosis.selected, std::vector<Kind>{Kind::kMotorTemperature}) << report;
  // The vehicle's own then joins the correction, unnamed, where it lowers the error beside the heating.
  EXPECT_EQ(diagnosis.background, std::vector<Kind>{Kind::kThrustLoss}) << report;
  const std::string& own = diagnosis.effects.at(static_cast<std::size_t>(Kind::kThrustLoss)).reason;
  EXPECT_EQ(own.rfind("modelled as the vehicle's own, not named", 0), 0u) << own;
  EXPECT_LT(diagnosis.heldout.after_rmse_pct, heating.heldout_rmse_pct) << report;
}

// A reference judges a motor heating read within flights by its change from the healthy flights
// alone (gap::judgedByReferenceAlone): parts assumed to spread so widely (20 % of thrust, every
// shape imitable) that nothing is named against them are in the healthy flights' fit too. Motors
// warming 20 C over each flight (its variance within flights about twice the day's between them),
// their thrust 0.2 %/C lower; the healthy flights warm alike at no cost. A supply resistance stays
// judged against the parts: what they imitate of the battery current moves with the payload.
TEST_F(SyntheticFlights, WithAReferenceAHeatingReadWithinFlightsIsJudgedByItsChangeNotByTheParts) {
  gap::DiagnosisConfig config;
  config.parts_spread.thrust_fraction = 0.2;
  config.parts_spread.max_imitated_share = 0.0;
  World heating;
  heating.motor_temperature = true;
  heating.motor_warming_c = 20.0;
  heating.warming_heats = true;
  heating.no_current = true;
  World healthy = heating;
  heating.motor_per_c = -0.002;
  const auto reason = [](const gap::Diagnosis& d, Kind kind) { return d.effects.at(static_cast<std::size_t>(kind)).reason; };

  const gap::Diagnosis against_parts = gap::diagnoseGap(model_, vehicle_, flights(heating), config);
  EXPECT_TRUE(against_parts.selected.empty());
  EXPECT_EQ(reason(against_parts, Kind::kMotorTemperature).rfind("modelled as the vehicle's own, not named: changes the thrust by at most", 0), 0u)
      << reason(against_parts, Kind::kMotorTemperature);

  gap::DiagnosisConfig with_reference = config;
  with_reference.reference_effects = gap::fitReferenceEffects(model_, vehicle_, flights(healthy, 1), with_reference);
  ASSERT_EQ(with_reference.reference_effects.count(Kind::kMotorTemperature), 1u);
  const gap::Diagnosis against_reference = gap::diagnoseGap(model_, vehicle_, flights(heating), with_reference);
  EXPECT_EQ(against_reference.selected, std::vector<Kind>{Kind::kMotorTemperature})
      << gap::gapReportMarkdown(against_reference, model_, "cmd");

  World wired;
  wired.supply_resistance = 0.03;
  gap::DiagnosisConfig wiring_reference = config;
  wiring_reference.reference_effects = gap::fitReferenceEffects(model_, vehicle_, flights(World{}, 1), wiring_reference);
  ASSERT_EQ(wiring_reference.reference_effects.count(Kind::kSupplyResistance), 1u);
  const gap::Diagnosis wiring = gap::diagnoseGap(model_, vehicle_, flights(wired), wiring_reference);
  EXPECT_TRUE(wiring.selected.empty());
  EXPECT_EQ(reason(wiring, Kind::kSupplyResistance).rfind("modelled as the vehicle's own, not named: changes the thrust by at most", 0), 0u)
      << reason(wiring, Kind::kSupplyResistance);
}

// min_improvement_pct (0.0925 points, the family's null flights' largest fall 25 % up) holds from
// both sides: the motors' heating at -0.0006 per C lowers these flights' held-out error by 0.07
// points and is not named, at -0.0008 per C by 0.12 and is (measured 2026-12-06); halved, the
// threshold names the first, raised by half it leaves the second unnamed. So does
// max_mean_square_ratio (0.9) from below: the second's mean square falls to 0.62 of what it was.
TEST_F(SyntheticFlights, TheImprovementThresholdLiesBetweenTwoSmallHeatings) {
  // 1: the heating named alone; 0: nothing named, nothing ambiguous; -1: anything else.
  const auto verdict = [this](double per_c, const gap::DiagnosisConfig& config) {
    World warm;
    warm.motor_temperature = true;
    warm.motor_per_c = per_c;
    warm.no_current = true;
    const gap::Diagnosis diagnosis = gap::diagnoseGap(model_, vehicle_, flights(warm), config);
    if (!diagnosis.ambiguous.empty()) return -1;
    if (diagnosis.selected.empty()) return 0;
    return diagnosis.selected == std::vector<Kind>{Kind::kMotorTemperature} ? 1 : -1;
  };
  gap::DiagnosisConfig config;
  EXPECT_EQ(verdict(-0.0006, config), 0);
  EXPECT_EQ(verdict(-0.0008, config), 1);
  const gap::DiagnosisConfig calibrated;
  config.min_improvement_pct = 0.5 * calibrated.min_improvement_pct;
  EXPECT_EQ(verdict(-0.0006, config), 1);
  config.min_improvement_pct = 1.5 * calibrated.min_improvement_pct;
  EXPECT_EQ(verdict(-0.0008, config), 0);
  config = calibrated;
  config.max_mean_square_ratio = 0.5 * calibrated.max_mean_square_ratio;
  EXPECT_EQ(verdict(-0.0008, config), 0);
}

namespace {

// validate()'s one line on `config`; "" when it accepts it.
std::string refusal(const gap::DiagnosisConfig& config) {
  try {
    config.validate();
  } catch (const pe::FieldError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(DiagnosisConfig, RefusesARegionalThresholdForAnEffectActingOnEveryBlockOrOutOfRange) {
  EXPECT_EQ(refusal(gap::DiagnosisConfig()), "");
  gap::DiagnosisConfig config;
  config.min_regional_improvement_pct[Kind::kThrustLoss] = 0.2;
  EXPECT_EQ(refusal(config),
            "min_regional_improvement_pct.thrust_loss: acts on every block: it has no blocks of its own to be judged on");
  config = gap::DiagnosisConfig();
  config.min_regional_improvement_pct[Kind::kGroundEffect] = -0.1;
  EXPECT_EQ(refusal(config), "min_regional_improvement_pct.ground_effect: -0.1 is outside 0..50 %");
  // A later round's threshold needs the first round's, and is no lower than it.
  config = gap::DiagnosisConfig();
  config.min_later_regional_improvement_pct[Kind::kClimbInflow] = 1.0;
  EXPECT_EQ(refusal(config),
            "min_later_regional_improvement_pct.climb_inflow: needs a min_regional_improvement_pct: an effect not "
            "judged where its law acts in a first round is not judged there after one");
  config = gap::DiagnosisConfig();
  config.min_later_regional_improvement_pct[Kind::kGroundEffect] = 0.1;
  EXPECT_EQ(refusal(config),
            "min_later_regional_improvement_pct.ground_effect: 0.1 % is below min_regional_improvement_pct.ground_effect "
            "(0.14 %): what an earlier law leaves there is no less than what the model family's mismatch gives");
}

// A propeller at 85 % with the payloads' moments as the basis and no battery current: 15 % is
// within three times what healthy vehicles show, so no suspect, but the motor stands out of its
// balance; a thrust loss or an ESC offset fitted on every rotor would take up its quarter of the
// vehicle's thrust, and on top of that motor's factor neither is left to name (lacking_motor.cpp).
TEST_F(SyntheticFlights, AMotorThatLacksBelowASuspectsBarExplainsAGlobalEffectAway) {
  World world;
  world.weak_motor = 2;
  world.weak_factor = 0.85;
  world.no_current = true;
  const gap::Diagnosis diagnosis = diagnose(world);
  EXPECT_EQ(diagnosis.motors.basis, gap::MotorBasis::kPayloads);
  EXPECT_FALSE(diagnosis.motors.suspect_channel);
  EXPECT_TRUE(diagnosis.selected.empty()) << testing::PrintToString(diagnosis.selected.size());
  const std::string explained = "not named: one motor explains it: channel 3 lacks 15.0 % +- 0.1 of its thrust in the "
                                "moment balance (a suspect needs more than 5 % and three times the +-6.7 % spread "
                                "healthy vehicles show), and on top of that motor's factor it no longer lowers the held-out "
                                "error as a name needs: what it takes up is that rotor's";
  for (pe::effects::Kind kind : {pe::effects::Kind::kThrustLoss, pe::effects::Kind::kEscOffset}) {
    const auto effect = std::find_if(diagnosis.effects.begin(), diagnosis.effects.end(),
                                     [kind](const gap::EffectResult& e) { return e.kind == kind; });
    ASSERT_NE(effect, diagnosis.effects.end());
    EXPECT_EQ(effect->reason, explained) << pe::effects::kindName(kind);
  }
  // The same motor at 97 %: below what healthy rotors differ by, it explains nothing away.
  world.weak_factor = 0.97;
  for (const gap::EffectResult& effect : diagnose(world).effects) {
    EXPECT_EQ(effect.reason.find("one motor explains it"), std::string::npos) << effect.reason;
  }
}
