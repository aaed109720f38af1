// Each switchable effect moves the simulated thrust in the direction, and by the amount, its
// formula says: checked where it applies (bench and/or flight), against the formula evaluated
// independently of the simulator's code path.
#include <gtest/gtest.h>

#include <cmath>

#include "propulsion_estimator/core/bench_simulator.h"
#include "propulsion_estimator/core/flight_profile_yaml.h"
#include "propulsion_estimator/core/flight_simulator.h"
#include "propulsion_estimator/core/power_train.h"
#include "propulsion_estimator/core/sim_params_yaml.h"
#include "propulsion_estimator/core/units.h"
#include "propulsion_estimator/core/vehicle_urdf.h"
#include "recording_flight_sink.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

pe::SimParams thesisParams() { return pe::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml")); }

// Noise-free sweep at 12 V from 1500 to 1800 us in 50 us steps.
pe::BenchLog sweepTruth(const pe::SimEffects& effects, double step_duration_s = 1.0) {
  const pe::SimParams params = thesisParams();
  pe::BenchExperiment sweep = pe::thesisBenchExperiment(pe::BenchExperimentKind::kPwmSweep, params);
  sweep.voltages_v = {12.0};
  sweep.pwm_start_us = 1500.0;
  sweep.pwm_end_us = 1800.0;
  sweep.pwm_step_us = 50.0;
  sweep.step_duration_s = step_duration_s;
  pe::BenchLog truth;
  pe::simulateBench(params, effects, sweep, 7, &truth);
  return truth;
}

double column(const pe::BenchLog& log, pe::BenchColumn c, std::size_t row) { return log.column(c)[row]; }

// Isolated-rotor thrust at a rotor speed, from the propeller law (not the simulator's code).
double isolatedThrust(const pe::SimParams& params, double density, double rpm) {
  const double n = rpm / 60.0;
  return params.chain.propeller.thrust_coefficient * density * n * n * std::pow(params.chain.propeller.diameter_m, 4);
}

struct Flight {
  RecordingFlightSink sink;
  pe::FlightResult result;
  pe::FlightProfile profile;
};

Flight fly(const pe::SimEffects& effects) {
  Flight flight;
  flight.profile = pe::loadFlightProfileFile(repoPath("config/sim/default_flight.yaml"));
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(flight.profile.vehicle.urdf_path);
  flight.result = pe::simulateFlight(thesisParams(), effects, flight.profile, vehicle, 3, &flight.sink);
  return flight;
}

// Mean pulse width over all motors in manifest segment `index`.
double meanHoverPwm(const Flight& flight, std::size_t index) {
  const pe::ManifestSegment& segment = flight.result.segments.at(index);
  double sum = 0.0;
  int count = 0;
  for (const pe::TruthSample& truth : flight.sink.truths) {
    if (truth.time_s < segment.start_s || truth.time_s > segment.end_s) continue;
    for (const pe::MotorTruth& motor : truth.motors) {
      sum += motor.pwm_us;
      ++count;
    }
  }
  return sum / count;
}

// In every truth sample, each rotor's thrust on the airframe equals the isolated rotor's thrust at
// its true speed times the effect terms reported with it.
void expectThrustIsIsolatedTimesTerms(const Flight& flight, double density) {
  const pe::SimParams params = thesisParams();
  for (const pe::TruthSample& truth : flight.sink.truths) {
    for (const pe::MotorTruth& motor : truth.motors) {
      const double expected = isolatedThrust(params, density, motor.rpm) * motor.ground_effect_factor *
                              truth.climb_factor * truth.thrust_loss_factor;
      ASSERT_NEAR(motor.thrust_n, expected, 1e-9 + 1e-9 * expected) << "t = " << truth.time_s;
    }
  }
}

}  // namespace

TEST(SupplyResistance, EscsSeeTheSensedVoltageLessRTimesCurrent) {
  // Bench at a regulated 12 V with 0.1 ohm between the voltage sensor and the ESC: the thrust is
  // the effect-free thrust at 12 V - 0.1 ohm x I.
  pe::SimEffects effects;
  effects.supply_resistance_ohm = 0.1;
  const pe::BenchLog with = sweepTruth(effects);
  const pe::BenchLog without = sweepTruth({});
  const pe::SimParams params = thesisParams();
  const pe::PropulsionChain chain(params.chain);
  for (std::size_t row = 0; row < with.rows(); ++row) {
    const double pwm = column(with, pe::BenchColumn::kPwm, row);
    EXPECT_DOUBLE_EQ(column(with, pe::BenchColumn::kVoltage, row), 12.0);
    const double esc_voltage = 12.0 - 0.1 * column(with, pe::BenchColumn::kCurrent, row);
    const double expected = chain
                                .steady({params.chain.esc.duty(pwm), esc_voltage, params.bench.air.densityKgM3(),
                                         params.chain.motor.reference_temperature_c})
                                .thrust_n;
    // 1e-4: after the 1 s dwell the rotor is within e^-11 of its steady speed.
    EXPECT_NEAR(column(with, pe::BenchColumn::kThrust, row), expected, 1e-4 * expected) << pwm;
    EXPECT_LT(column(with, pe::BenchColumn::kThrust, row), column(without, pe::BenchColumn::kThrust, row)) << pwm;
  }
}

TEST(SupplyResistance, RaisesTheHoverPulseWidthInFlight) {
  pe::SimEffects effects;
  effects.supply_resistance_ohm = 0.05;
  const Flight with = fly(effects);
  const Flight without = fly({});
  for (const pe::TruthSample& truth : with.sink.truths) {
    ASSERT_NEAR(truth.esc_voltage_v, truth.battery_voltage_v - 0.05 * truth.battery_current_a, 1e-9);
  }
  EXPECT_GT(meanHoverPwm(with, 0), meanHoverPwm(without, 0) + 10.0);
}

TEST(AirDensity, ThrustScalesWithDensityAtFixedRotorSpeed) {
  // 35 C and 90 kPa: density ratio 0.848. At fixed rotor speed thrust / (rho n^2) is the same
  // constant CT D^4 in both airs.
  pe::SimEffects effects;
  effects.air = pe::AirConditions{35.0, 90000.0};
  const pe::SimParams params = thesisParams();
  const double thin = effects.air->densityKgM3();
  const double bench = params.bench.air.densityKgM3();
  const pe::BenchLog with = sweepTruth(effects);
  const pe::BenchLog without = sweepTruth({});
  for (std::size_t row = 0; row < with.rows(); ++row) {
    const double thrust_thin = column(with, pe::BenchColumn::kThrust, row);
    const double thrust_bench = column(without, pe::BenchColumn::kThrust, row);
    EXPECT_NEAR(thrust_thin, isolatedThrust(params, thin, column(with, pe::BenchColumn::kRpm, row)), 1e-9);
    EXPECT_NEAR(thrust_bench, isolatedThrust(params, bench, column(without, pe::BenchColumn::kRpm, row)), 1e-9);
    // At fixed PWM the lighter load lets the rotor speed up, which recovers part of the loss:
    // thrust falls, but by less than the density.
    EXPECT_GT(column(with, pe::BenchColumn::kRpm, row), column(without, pe::BenchColumn::kRpm, row));
    EXPECT_LT(thrust_thin / thrust_bench, 1.0);
    EXPECT_GT(thrust_thin / thrust_bench, thin / bench);
  }
  EXPECT_EQ(with.metadata.at("air_temperature_c"), "35");
  EXPECT_EQ(with.metadata.at("air_pressure_pa"), "90000");
}

TEST(AirDensity, FlightAirShowsInTheBarometerAndTheTruth) {
  pe::SimEffects effects;
  effects.air = pe::AirConditions{35.0, 90000.0};
  const Flight flight = fly(effects);
  EXPECT_NEAR(flight.sink.truths.front().density_ratio,
              effects.air->densityKgM3() / thesisParams().bench.air.densityKgM3(), 1e-12);
  EXPECT_NEAR(flight.sink.pressures.front().value,
              90000.0 * std::exp(-pe::kStandardGravity * 0.12 / (287.058 * 308.15)), 6.0);
  EXPECT_NEAR(flight.sink.air_temperatures.front().value, 35.0, 0.3);
  expectThrustIsIsolatedTimesTerms(flight, effects.air->densityKgM3());
}

TEST(GroundEffect, FactorIsCheesemanBennettScaledByStrength) {
  const double radius = 0.1194;
  for (double z : {0.15, 0.24, 0.5, 2.0}) {
    const double cheeseman_bennett = 1.0 / (1.0 - std::pow(radius / (4.0 * z), 2));
    EXPECT_NEAR(pe::groundEffectFactor(radius, z, 1.0), cheeseman_bennett, 1e-12);
    EXPECT_NEAR(pe::groundEffectFactor(radius, z, 0.5), 1.0 + 0.5 * (cheeseman_bennett - 1.0), 1e-12);
  }
  // Below half a radius the formula is out of its range and is held at its value there.
  EXPECT_DOUBLE_EQ(pe::groundEffectFactor(radius, 0.01, 1.0), 1.0 / (1.0 - 0.25));
}

TEST(GroundEffect, NearTheGroundTheRotorsLiftMoreAtTheSameSpeed) {
  pe::SimEffects effects;
  effects.ground_effect_strength = 1.0;
  const Flight with = fly(effects);
  const Flight without = fly({});
  expectThrustIsIsolatedTimesTerms(with, thesisParams().bench.air.densityKgM3());
  // Manifest segment 2 is the hover at 0.2 m: rotors 0.235 m up, factor 1/(1 - (R/4z)^2) = 1.016.
  const pe::ManifestSegment& low = with.result.segments.at(2);
  const double radius = thesisParams().chain.propeller.radiusM();
  for (const pe::TruthSample& truth : with.sink.truths) {
    if (truth.time_s < low.start_s || truth.time_s > low.end_s) continue;
    const double rotor_height = truth.height_m + 0.035;  // rotor planes 35 mm above base_link
    for (const pe::MotorTruth& motor : truth.motors) {
      EXPECT_NEAR(motor.ground_effect_factor, 1.0 / (1.0 - std::pow(radius / (4.0 * rotor_height), 2)), 2e-3);
      EXPECT_GT(motor.ground_effect_factor, 1.012);
    }
  }
  // The extra lift lets the autopilot hover on a lower pulse width; at 5 m nothing changes.
  EXPECT_LT(meanHoverPwm(with, 2), meanHoverPwm(without, 2) - 2.0);
  EXPECT_NEAR(meanHoverPwm(with, 1), meanHoverPwm(without, 1), 0.5);
}

TEST(ThrustLoss, TheAirframeKeepsExactlyOneMinusTheFraction) {
  pe::SimEffects effects;
  effects.thrust_loss_fraction = 0.05;
  const Flight with = fly(effects);
  const Flight without = fly({});
  expectThrustIsIsolatedTimesTerms(with, thesisParams().bench.air.densityKgM3());
  for (const pe::TruthSample& truth : with.sink.truths) ASSERT_DOUBLE_EQ(truth.thrust_loss_factor, 0.95);
  // The rotors must make 1/0.95 of the weight: more pulse width for the same vehicle.
  EXPECT_GT(meanHoverPwm(with, 0), meanHoverPwm(without, 0) + 10.0);
  const pe::SimParams params = thesisParams();
  const pe::ManifestSegment& hover = with.result.segments.at(0);
  double isolated = 0.0;
  int samples = 0;
  for (const pe::TruthSample& truth : with.sink.truths) {
    if (truth.time_s < hover.start_s || truth.time_s > hover.end_s) continue;
    for (const pe::MotorTruth& motor : truth.motors)
      isolated += isolatedThrust(params, truth.air_density_kg_m3, motor.rpm);
    ++samples;
  }
  EXPECT_NEAR(isolated / samples, hover.mass_kg * pe::kStandardGravity / 0.95,
              0.005 * hover.mass_kg * pe::kStandardGravity);
}

TEST(MotorTemperature, OperatingPointFollowsTheWindingTemperature) {
  // Poorly cooled motors (5 C/W) heat during the sweep; every row is the steady state of a motor
  // whose resistance and flux are those of its temperature, and differs from the cold motor's.
  pe::SimEffects effects;
  effects.motor_thermal_resistance_c_per_w = 5.0;
  const pe::BenchLog hot = sweepTruth(effects, 30.0);
  const pe::BenchLog cold = sweepTruth({}, 30.0);
  const pe::SimParams params = thesisParams();
  const pe::PropulsionChain chain(params.chain);
  for (std::size_t row = 0; row < hot.rows(); ++row) {
    const double pwm = column(hot, pe::BenchColumn::kPwm, row);
    const double temperature = column(hot, pe::BenchColumn::kMotorTemp, row);
    const pe::ChainState expected =
        chain.steady({params.chain.esc.duty(pwm), 12.0, params.bench.air.densityKgM3(), temperature});
    EXPECT_NEAR(column(hot, pe::BenchColumn::kThrust, row), expected.thrust_n, 1e-3 * expected.thrust_n) << pwm;
    EXPECT_NEAR(column(hot, pe::BenchColumn::kCurrent, row), expected.input_current_a, 1e-3 * expected.input_current_a);
  }
  // By the end the windings are far above the 25 C reference, and the operating point has moved.
  const std::size_t last = hot.rows() - 1;
  EXPECT_GT(column(hot, pe::BenchColumn::kMotorTemp, last), 60.0);
  EXPECT_GT(std::fabs(column(hot, pe::BenchColumn::kThrust, last) / column(cold, pe::BenchColumn::kThrust, last) - 1.0),
            0.005);
}

TEST(ClimbInflow, ThrustChangesByTheFactorPerMetrePerSecond) {
  pe::SimEffects effects;
  effects.climb_inflow_per_m_s = 0.05;
  EXPECT_DOUBLE_EQ(pe::rotorEffectTerms(effects, 0.12, 5.0, 2.0).climb, 0.9);
  EXPECT_DOUBLE_EQ(pe::rotorEffectTerms(effects, 0.12, 5.0, -1.0).climb, 1.05);
  const Flight flight = fly(effects);
  expectThrustIsIsolatedTimesTerms(flight, thesisParams().bench.air.densityKgM3());
  double lowest = 1.0;
  for (const pe::TruthSample& truth : flight.sink.truths) {
    ASSERT_NEAR(truth.climb_factor, 1.0 - 0.05 * truth.vertical_speed_m_s, 1e-12);
    lowest = std::min(lowest, truth.climb_factor);
  }
  EXPECT_LT(lowest, 0.96);  // the 1 m/s climbs lose ~5 %
}

TEST(EscOffset, ThrustAtXWithOffsetEqualsThrustAtXMinusOffsetWithout) {
  const pe::SimParams params = thesisParams();
  pe::SimEffects effects;
  effects.esc_offset_us = 20.0;
  pe::PowerTrain shifted(pe::PropulsionChain(params.chain), 1, effects, 22.0);
  pe::PowerTrain reference(pe::PropulsionChain(params.chain), 1, {}, 22.0);
  const pe::Supply supply{11.5, 0.015};
  for (double pwm = 1500.0; pwm <= 1800.0; pwm += 0.5) {
    const double a = shifted.step({pwm}, supply, params.bench.air, 0.01).motors[0].thrust_n;
    const double b = reference.step({pwm - 20.0}, supply, params.bench.air, 0.01).motors[0].thrust_n;
    ASSERT_DOUBLE_EQ(a, b) << pwm;
  }
}

TEST(EscOffset, TheAutopilotHoversTheOffsetHigher) {
  pe::SimEffects effects;
  effects.esc_offset_us = 20.0;
  const Flight with = fly(effects);
  const Flight without = fly({});
  for (std::size_t i = 0; i < with.result.segments.size(); ++i) {
    EXPECT_NEAR(meanHoverPwm(with, i) - meanHoverPwm(without, i), 20.0, 2.0) << "segment " << i;
  }
}

TEST(SimEffects, AllOffByDefaultAndSummarised) {
  EXPECT_EQ(pe::SimEffects{}.summary(), "none");
  pe::SimEffects effects;
  effects.ground_effect_strength = 1.0;
  effects.thrust_loss_fraction = 0.05;
  EXPECT_EQ(effects.summary(), "ground_effect(strength=1) thrust_loss(fraction=0.05)");
  const pe::RotorEffectTerms terms = pe::rotorEffectTerms({}, 0.12, 0.2, 3.0);
  EXPECT_EQ(terms.product(), 1.0);
}
