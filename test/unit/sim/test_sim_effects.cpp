// Each switchable effect moves the simulated thrust in the direction, and by the amount, its
// formula says: checked where it applies (bench and/or flight), against the formula evaluated
// independently of the simulator's code path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/sim/stand/bench_simulator.h"
#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"
#include "propulsion_estimator/sim/flight/flight_simulator.h"
#include "propulsion_estimator/sim/physics/power_train.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "hand_rotor.h"
#include "recording_flight_sink.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

pe::sim::SimParams thesisParams() {
  return pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
}

// Noise-free sweep at 12 V from 1500 to 1800 us in 50 us steps.
pe::BenchLog sweepTruth(const pe::sim::SimEffects& effects, double step_duration_s = 1.0) {
  const pe::sim::SimParams params = thesisParams();
  pe::sim::BenchExperiment sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.voltages_v = {12.0};
  sweep.pwm_start_us = 1500.0;
  sweep.pwm_end_us = 1800.0;
  sweep.pwm_step_us = 50.0;
  sweep.step_duration_s = step_duration_s;
  pe::BenchLog truth;
  pe::sim::simulateBench(params, effects, sweep, 7, &truth);
  return truth;
}

double column(const pe::BenchLog& log, pe::BenchColumn c, std::size_t row) { return log.column(c)[row]; }

// Isolated-rotor thrust at a rotor speed, from the propeller law (not the simulator's code).
double isolatedThrust(const pe::sim::SimParams& params, double density, double rpm) {
  const double n = rpm / 60.0;
  return params.chain.propeller.thrust_coefficient * density * n * n * std::pow(params.chain.propeller.diameter_m, 4);
}

// The brushed-DC-equivalent motor written out here, independently of the simulator's code, at
// winding temperature T: copper resistance R_w(T) = R_w(T0) (1 + 0.00393 (T - 20)) / (1 + 0.00393
// (T0 - 20)) (IEC 60028 gives 0.00393 /K at 20 C; referred to T0 = 25 C it is 0.00386 /K), torque
// constant Kt(T) = Kt0 (1 + alpha (T - T0)) with Kt0 = 60 / (2 pi Kv) and alpha the magnets'
// remanence coefficient. With R = R_w + R_esc and Q = kQ w^2 (kQ = CQ rho D^5 / (2 pi)^2), the
// torque balance Kt (I - I0) = Q with I = (d V - Kt w) / R is kQ w^2 + (Kt^2 / R) w - Kt (d V / R - I0) = 0.
struct SteadyPoint {
  double omega_rad_s = 0.0;
  double thrust_n = 0.0;
  double motor_current_a = 0.0;
  double input_current_a = 0.0;
};

SteadyPoint brushedDcSteadyState(const pe::sim::SimParams& params, double pwm_us, double esc_voltage_v, double density,
                                 double winding_c) {
  const pe::sim::BldcMotorParams& motor = params.chain.motor;
  const pe::sim::PropellerParams& propeller = params.chain.propeller;
  const double pi = 3.14159265358979323846;
  const double duty = std::clamp(
      (pwm_us - params.chain.esc.pwm_zero_us) / (params.chain.esc.pwm_full_us - params.chain.esc.pwm_zero_us), 0.0,
      1.0);
  const double t0 = motor.reference_temperature_c;
  const double kt =
      60.0 / (2.0 * pi * motor.kv_rpm_per_v) * (1.0 + motor.flux_temperature_coefficient_per_c * (winding_c - t0));
  const double r = motor.winding_resistance_ohm * (1.0 + 0.00393 * (winding_c - 20.0)) / (1.0 + 0.00393 * (t0 - 20.0)) +
                   params.chain.esc.resistance_ohm;
  const double kq = propeller.torque_coefficient * density * std::pow(propeller.diameter_m, 5) / (4.0 * pi * pi);
  const double a = kq, b = kt * kt / r, c = -kt * (duty * esc_voltage_v / r - motor.no_load_current_a);
  SteadyPoint point;
  point.omega_rad_s = (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
  point.thrust_n = isolatedThrust(params, density, point.omega_rad_s * 60.0 / (2.0 * pi));
  point.motor_current_a = (duty * esc_voltage_v - kt * point.omega_rad_s) / r;
  point.input_current_a = duty * point.motor_current_a;
  return point;
}

struct Flight {
  RecordingFlightSink sink;
  pe::sim::FlightResult result;
  pe::sim::FlightProfile profile;
};

Flight fly(const pe::sim::SimEffects& effects) {
  Flight flight;
  flight.profile = pe::sim::loadFlightProfileFile(repoPath("config/sim/default_flight.yaml"));
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(flight.profile.vehicle.urdf_path);
  flight.result = pe::sim::simulateFlight(thesisParams(), effects, flight.profile, vehicle, 3, &flight.sink);
  return flight;
}

// Mean battery current (truth) over [from_s, to_s].
double meanCurrent(const Flight& flight, double from_s, double to_s) {
  double sum = 0.0;
  int count = 0;
  for (const pe::sim::TruthSample& truth : flight.sink.truths) {
    if (truth.time_s < from_s || truth.time_s > to_s) continue;
    sum += truth.battery_current_a;
    ++count;
  }
  return sum / count;
}

// Mean pulse width over all motors in manifest segment `index`.
double meanHoverPwm(const Flight& flight, std::size_t index) {
  const pe::ManifestSegment& segment = flight.result.segments.at(index);
  double sum = 0.0;
  int count = 0;
  for (const pe::sim::TruthSample& truth : flight.sink.truths) {
    if (truth.time_s < segment.start_s || truth.time_s > segment.end_s) continue;
    for (const pe::sim::MotorTruth& motor : truth.motors) {
      sum += motor.pwm_us;
      ++count;
    }
  }
  return sum / count;
}

// In every truth sample, each rotor's thrust on the airframe equals the isolated rotor's thrust at
// its true speed times the effect terms reported with it.
void expectThrustIsIsolatedTimesTerms(const Flight& flight, double density) {
  const pe::sim::SimParams params = thesisParams();
  for (const pe::sim::TruthSample& truth : flight.sink.truths) {
    for (const pe::sim::MotorTruth& motor : truth.motors) {
      const double expected = isolatedThrust(params, density, motor.rpm) * motor.ground_effect_factor *
                              motor.climb_factor * truth.thrust_loss_factor;
      ASSERT_NEAR(motor.thrust_n, expected, 1e-9 + 1e-9 * expected) << "t = " << truth.time_s;
    }
  }
}

}  // namespace

TEST(SupplyResistance, EscsSeeTheSensedVoltageLessRTimesCurrent) {
  // Bench at a regulated 12 V with 0.1 ohm between the voltage sensor and the ESC: the thrust is
  // the effect-free thrust at 12 V - 0.1 ohm x I.
  pe::sim::SimEffects effects;
  effects.supply_resistance_ohm = 0.1;
  const pe::BenchLog with = sweepTruth(effects);
  const pe::BenchLog without = sweepTruth({});
  const pe::sim::SimParams params = thesisParams();
  const pe::sim::PropulsionChain chain(params.chain);
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

TEST(SupplyResistance, OnABatteryTheVoltageSensorReadsUpstreamOfThePath) {
  // A discharge at 1700 us with 0.1 ohm between the bench's voltage sensor (at the pack's
  // terminals) and the ESC: every row's thrust is the written-out motor's at the sensed voltage
  // less 0.1 ohm x the sensed current, and visibly not at the sensed voltage itself.
  const pe::sim::SimParams params = thesisParams();
  const double density = params.bench.air.densityKgM3();
  pe::sim::BenchExperiment discharge = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kDischarge, params);
  discharge.pwms_us = {1700.0};
  discharge.sample_interval_s = 20.0;
  discharge.initial_soc = 0.5;
  pe::sim::SimEffects effects;
  effects.supply_resistance_ohm = 0.1;
  pe::BenchLog with, without;
  pe::sim::simulateBench(params, effects, discharge, 4, &with);
  pe::sim::simulateBench(params, {}, discharge, 4, &without);
  ASSERT_GT(with.rows(), 20u);
  for (std::size_t row = 0; row < with.rows(); ++row) {
    const double sensed = column(with, pe::BenchColumn::kVoltage, row);
    const double current = column(with, pe::BenchColumn::kCurrent, row);
    const double thrust = column(with, pe::BenchColumn::kThrust, row);
    const double expected = brushedDcSteadyState(params, 1700.0, sensed - 0.1 * current, density, 25.0).thrust_n;
    ASSERT_NEAR(thrust, expected, 1e-4 * expected) << "row " << row;
    ASSERT_LT(thrust, 0.97 * brushedDcSteadyState(params, 1700.0, sensed, density, 25.0).thrust_n) << "row " << row;
  }
  for (std::size_t row = 0; row < without.rows(); ++row) {
    const double expected =
        brushedDcSteadyState(params, 1700.0, column(without, pe::BenchColumn::kVoltage, row), density, 25.0).thrust_n;
    ASSERT_NEAR(column(without, pe::BenchColumn::kThrust, row), expected, 1e-4 * expected) << "row " << row;
  }
}

TEST(SupplyResistance, RaisesTheHoverPulseWidthInFlight) {
  pe::sim::SimEffects effects;
  effects.supply_resistance_ohm = 0.05;
  const Flight with = fly(effects);
  const Flight without = fly({});
  for (const pe::sim::TruthSample& truth : with.sink.truths) {
    ASSERT_NEAR(truth.esc_voltage_v, truth.battery_voltage_v - 0.05 * truth.battery_current_a, 1e-9);
  }
  EXPECT_GT(meanHoverPwm(with, 0), meanHoverPwm(without, 0) + 10.0);
}

TEST(AirDensity, ThrustScalesWithDensityAtFixedRotorSpeed) {
  // 35 C and 90 kPa: density ratio 0.848. At fixed rotor speed thrust / (rho n^2) is the same
  // constant CT D^4 in both airs.
  pe::sim::SimEffects effects;
  effects.air = pe::sim::AirConditions{35.0, 90000.0};
  const pe::sim::SimParams params = thesisParams();
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
  pe::sim::SimEffects effects;
  effects.air = pe::sim::AirConditions{35.0, 90000.0};
  const Flight flight = fly(effects);
  EXPECT_NEAR(flight.sink.truths.front().density_ratio,
              effects.air->densityKgM3() / thesisParams().bench.air.densityKgM3(), 1e-12);
  // The barometer at base_link, averaged over the wait on the ground (50 readings, 1.2 Pa each:
  // 0.17 Pa) and over the 5 m hover (270 readings: 0.07 Pa), against the barometric formula at the
  // true heights. On the ground the 0.12 m gear alone is 1.2 Pa: a 0.5 Pa tolerance sees it.
  const auto pressureAt = [](double height_m) {
    return 90000.0 * std::exp(-pe::kStandardGravity * height_m / (287.058 * (35.0 + 273.15)));
  };
  const auto meanOver = [&](double from_s, double to_s) {
    double pressure = 0.0, height = 0.0;
    int pressures = 0, heights = 0;
    for (const pe::sim::ScalarSample& s : flight.sink.pressures) {
      if (s.time_s < from_s || s.time_s > to_s) continue;
      pressure += s.value;
      ++pressures;
    }
    for (const pe::sim::TruthSample& t : flight.sink.truths) {
      if (t.time_s < from_s || t.time_s > to_s) continue;
      height += t.height_m;
      ++heights;
    }
    return std::pair{pressure / pressures, height / heights};
  };
  const auto [ground_pressure, ground_height] = meanOver(0.0, 4.9);
  EXPECT_NEAR(ground_height, 0.12, 0.002);
  EXPECT_NEAR(ground_pressure, pressureAt(ground_height), 0.5);
  EXPECT_GT(std::fabs(pressureAt(ground_height) - 90000.0), 1.0);
  const auto [high_pressure, high_height] =
      meanOver(flight.result.segments[1].start_s, flight.result.segments[1].end_s);
  EXPECT_NEAR(high_height, 5.0, 0.02);
  EXPECT_NEAR(high_pressure, pressureAt(high_height), 0.3);
  EXPECT_NEAR(flight.sink.air_temperatures.front().value, 35.0, 0.3);
  expectThrustIsIsolatedTimesTerms(flight, effects.air->densityKgM3());
}

TEST(GroundEffect, FactorIsCheesemanBennettScaledByStrength) {
  const double radius = 0.1194;
  for (double z : {0.15, 0.24, 0.5, 2.0}) {
    const double cheeseman_bennett = 1.0 / (1.0 - std::pow(radius / (4.0 * z), 2));
    EXPECT_NEAR(pe::sim::groundEffectFactor(radius, z, 1.0), cheeseman_bennett, 1e-12);
    EXPECT_NEAR(pe::sim::groundEffectFactor(radius, z, 0.5), 1.0 + 0.5 * (cheeseman_bennett - 1.0), 1e-12);
  }
  // Below half a radius the formula is out of its range and is held at its value there.
  EXPECT_DOUBLE_EQ(pe::sim::groundEffectFactor(radius, 0.01, 1.0), 1.0 / (1.0 - 0.25));
}

TEST(GroundEffect, NearTheGroundTheRotorsLiftMoreAtTheSameSpeed) {
  pe::sim::SimEffects effects;
  effects.ground_effect_strength = 1.0;
  const Flight with = fly(effects);
  const Flight without = fly({});
  expectThrustIsIsolatedTimesTerms(with, thesisParams().bench.air.densityKgM3());
  // Manifest segment 2 is the hover at 0.2 m: rotors 0.235 m up, where the ground takes eps =
  // (R/4z)^2 = 1.6 % off the induced inflow. At fixed speed the rotor gains 0.68 eps = 1.1 % of
  // thrust (blade-element momentum theory), where Cheeseman-Bennett's equal-power ratio would say 1.6 %.
  const pe::ManifestSegment& low = with.result.segments.at(2);
  const pe::sim::PropellerParams& propeller = thesisParams().chain.propeller;
  const double radius = propeller.radiusM();
  // Blade-element momentum theory at first order (rotor_inflow.h): dT/T = lambda_0 / (Theta -
  // lambda_0 / 2) eps, with the blade calibrated on the propeller's static coefficients.
  const HandRotor hand(propeller);
  const double share = hand.lambda0 / (hand.theta - hand.lambda0 / 2.0);
  EXPECT_NEAR(share, 0.679, 0.001);
  for (const pe::sim::TruthSample& truth : with.sink.truths) {
    if (truth.time_s < low.start_s || truth.time_s > low.end_s) continue;
    const double rotor_height = truth.height_m + 0.035;  // rotor planes 35 mm above base_link
    for (const pe::sim::MotorTruth& motor : truth.motors) {
      EXPECT_NEAR(motor.ground_effect_factor, 1.0 + share * std::pow(radius / (4.0 * rotor_height), 2), 2e-3);
      EXPECT_GT(motor.ground_effect_factor, 1.009);
    }
  }
  // The extra lift lets the autopilot hover on a lower pulse width; at 5 m nothing changes.
  EXPECT_LT(meanHoverPwm(with, 2), meanHoverPwm(without, 2) - 2.0);
  EXPECT_NEAR(meanHoverPwm(with, 1), meanHoverPwm(without, 1), 0.5);
  // Holding the thrust on slower rotors, whose torque the ground hardly changes, the motors draw
  // less current: 1.1 % less thrust per unit rotor speed squared is ~1.5 % less power.
  EXPECT_LT(meanCurrent(with, low.start_s, low.end_s), 0.99 * meanCurrent(without, low.start_s, low.end_s));
  const pe::ManifestSegment& high = with.result.segments.at(1);
  EXPECT_NEAR(meanCurrent(with, high.start_s, high.end_s) / meanCurrent(without, high.start_s, high.end_s), 1.0,
              0.002);
}

TEST(ThrustLoss, TheAirframeKeepsExactlyOneMinusTheFraction) {
  pe::sim::SimEffects effects;
  effects.thrust_loss_fraction = 0.05;
  const Flight with = fly(effects);
  const Flight without = fly({});
  expectThrustIsIsolatedTimesTerms(with, thesisParams().bench.air.densityKgM3());
  for (const pe::sim::TruthSample& truth : with.sink.truths) ASSERT_DOUBLE_EQ(truth.thrust_loss_factor, 0.95);
  // The rotors must make 1/0.95 of the weight: more pulse width for the same vehicle.
  EXPECT_GT(meanHoverPwm(with, 0), meanHoverPwm(without, 0) + 10.0);
  const pe::sim::SimParams params = thesisParams();
  const pe::ManifestSegment& hover = with.result.segments.at(0);
  double isolated = 0.0;
  int samples = 0;
  for (const pe::sim::TruthSample& truth : with.sink.truths) {
    if (truth.time_s < hover.start_s || truth.time_s > hover.end_s) continue;
    for (const pe::sim::MotorTruth& motor : truth.motors)
      isolated += isolatedThrust(params, truth.air_density_kg_m3, motor.rpm);
    ++samples;
  }
  EXPECT_NEAR(isolated / samples, hover.mass_kg * pe::kStandardGravity / 0.95,
              0.005 * hover.mass_kg * pe::kStandardGravity);
}

TEST(MotorTemperature, HotWindingsAtFixedPwmSpinFasterAndDrawMoreCurrent) {
  // At fixed duty the steady speed is w = (d V - I R) / Kt: the no-load speed d V / Kt over the
  // drop I R. From 25 to 100 deg C the NdFeB flux (Kt) falls 9 %, raising the no-load speed by
  // 10 %, while the copper's resistance rises 29 % (26 % with the ESC's), raising the drop by more
  // than half (R / Kt^2) - but at 1700 us and 12 V the drop is only 15 % of d V, so the weaker
  // field wins: the rotor spins faster and the thrust RISES, from 3.839 to 3.970 N. It would fall
  // only where the drop exceeds about 19 % of d V (heavy load, beyond 1900 us at 12 V). The motor
  // pays with current: a weaker Kt needs more amperes for the propeller's larger torque.
  const pe::sim::SimParams params = thesisParams();
  const double density = params.bench.air.densityKgM3();
  const SteadyPoint cold = brushedDcSteadyState(params, 1700.0, 12.0, density, 25.0);
  const SteadyPoint hot = brushedDcSteadyState(params, 1700.0, 12.0, density, 100.0);
  EXPECT_NEAR(cold.thrust_n, 3.839, 0.001);
  EXPECT_NEAR(hot.thrust_n, 3.970, 0.001);
  EXPECT_GT(hot.thrust_n, cold.thrust_n);
  EXPECT_GT(hot.input_current_a, 1.1 * cold.input_current_a);
  // The simulator's chain at the same points.
  const pe::sim::PropulsionChain chain(params.chain);
  const double duty = params.chain.esc.duty(1700.0);
  for (const auto& [celsius, expected] : {std::pair{25.0, cold}, std::pair{100.0, hot}}) {
    const pe::sim::ChainState state = chain.steady({duty, 12.0, density, celsius});
    EXPECT_NEAR(state.thrust_n, expected.thrust_n, 1e-9 * expected.thrust_n) << celsius;
    EXPECT_NEAR(state.input_current_a, expected.input_current_a, 1e-9 * expected.input_current_a) << celsius;
  }
}

TEST(MotorTemperature, TheBenchOperatingPointFollowsTheWindingTemperature) {
  // Poorly cooled motors (5 C/W) heat during a sweep of 30 s steps; every row is the steady state
  // of the written-out motor at the row's winding temperature, and above 60 deg C the hot rotor
  // gives more thrust and draws more current than the cold one (see the test above).
  pe::sim::SimEffects effects;
  effects.motor_thermal_resistance_c_per_w = 5.0;
  const pe::BenchLog hot = sweepTruth(effects, 30.0);
  const pe::BenchLog cold = sweepTruth({}, 30.0);
  const pe::sim::SimParams params = thesisParams();
  const double density = params.bench.air.densityKgM3();
  for (std::size_t row = 0; row < hot.rows(); ++row) {
    const double pwm = column(hot, pe::BenchColumn::kPwm, row);
    const SteadyPoint expected =
        brushedDcSteadyState(params, pwm, 12.0, density, column(hot, pe::BenchColumn::kMotorTemp, row));
    EXPECT_NEAR(column(hot, pe::BenchColumn::kThrust, row), expected.thrust_n, 1e-3 * expected.thrust_n) << pwm;
    EXPECT_NEAR(column(hot, pe::BenchColumn::kCurrent, row), expected.input_current_a, 1e-3 * expected.input_current_a)
        << pwm;
    // Without the effect the constants stay at the 25 deg C reference.
    const SteadyPoint reference = brushedDcSteadyState(params, pwm, 12.0, density, 25.0);
    EXPECT_NEAR(column(cold, pe::BenchColumn::kThrust, row), reference.thrust_n, 1e-3 * reference.thrust_n) << pwm;
  }
  const std::size_t last = hot.rows() - 1;
  EXPECT_GT(column(hot, pe::BenchColumn::kMotorTemp, last), 60.0);
  EXPECT_GT(column(hot, pe::BenchColumn::kThrust, last), 1.01 * column(cold, pe::BenchColumn::kThrust, last));
  EXPECT_GT(column(hot, pe::BenchColumn::kCurrent, last), 1.05 * column(cold, pe::BenchColumn::kCurrent, last));
}

TEST(MotorTemperature, HotMotorsHoverOnMorePower) {
  // In flight the autopilot holds the thrust, so the rotor speed and the propeller's torque Q stay;
  // a hot motor then needs I = I0 + Q / Kt(T) and the input power d V I = I (Kt w + R I): more
  // copper loss for the weaker field. Each truth sample's input power is that of the written-out
  // motor at its rotor speed and winding temperature (to the speed changes the control makes).
  pe::sim::SimEffects effects;
  effects.motor_thermal_resistance_c_per_w = 5.0;
  const Flight hot = fly(effects);
  const Flight cold = fly({});
  const pe::sim::SimParams params = thesisParams();
  const pe::sim::BldcMotorParams& motor = params.chain.motor;
  const double pi = 3.14159265358979323846;
  const pe::ManifestSegment& last = hot.result.segments.back();
  double simulated = 0.0, expected = 0.0, cold_power = 0.0, temperature = 0.0;
  int readings = 0;
  for (const pe::sim::TruthSample& truth : hot.sink.truths) {
    if (truth.time_s < last.start_s || truth.time_s > last.end_s) continue;
    for (const pe::sim::MotorTruth& m : truth.motors) {
      const double omega = m.rpm * 2.0 * pi / 60.0;
      const double t = m.winding_temperature_c;
      const double kt = 60.0 / (2.0 * pi * motor.kv_rpm_per_v) *
                        (1.0 + motor.flux_temperature_coefficient_per_c * (t - motor.reference_temperature_c));
      const double r = motor.winding_resistance_ohm * (1.0 + 0.00393 * (t - 20.0)) /
                           (1.0 + 0.00393 * (motor.reference_temperature_c - 20.0)) +
                       params.chain.esc.resistance_ohm;
      const double torque = params.chain.propeller.torque_coefficient * truth.air_density_kg_m3 *
                            std::pow(omega / (2.0 * pi), 2) * std::pow(params.chain.propeller.diameter_m, 5);
      const double current = motor.no_load_current_a + torque / kt;
      simulated += m.power_w;
      expected += current * (kt * omega + r * current);
      temperature += t;
      ++readings;
    }
  }
  for (const pe::sim::TruthSample& truth : cold.sink.truths) {
    if (truth.time_s < last.start_s || truth.time_s > last.end_s) continue;
    for (const pe::sim::MotorTruth& m : truth.motors) cold_power += m.power_w;
  }
  EXPECT_NEAR(simulated / expected, 1.0, 0.001);
  // The same segment of both flights (the same number of readings): the hot motors use more power.
  EXPECT_GT(simulated, 1.01 * cold_power);
  EXPECT_GT(temperature / readings, 45.0);
}

TEST(ClimbInflow, RotorsLoseThrustInAClimbAtFixedSpeedAndTheMotorsMakeUpForIt) {
  pe::sim::SimEffects effects;
  effects.climb_inflow_strength = 0.5;
  EXPECT_DOUBLE_EQ(pe::sim::rotorInflow(effects, 0.12, 5.0, 2.0, 0.0).axial_speed_m_s, 1.0);
  EXPECT_DOUBLE_EQ(pe::sim::rotorInflow(effects, 0.12, 5.0, -1.0, 0.0).axial_speed_m_s, -0.5);
  EXPECT_DOUBLE_EQ(pe::sim::rotorInflow(effects, 0.12, 5.0, 2.0, 0.0).ground_inflow_ratio, 1.0);
  effects.climb_inflow_strength = 1.0;
  const Flight flight = fly(effects);
  const Flight without = fly({});
  expectThrustIsIsolatedTimesTerms(flight, thesisParams().bench.air.densityKgM3());
  // Each rotor's factor at its speed against blade-element momentum theory worked by hand at the
  // vehicle's vertical speed, in the steady part of the 1 m/s climb and the 0.8 m/s descent
  // (elsewhere the rotors' axial speeds differ from the vehicle's vertical speed by its rotation);
  // in the descent the induced inflow rises about as fast as the rotor descends, and the thrust
  // hardly moves.
  const std::vector<pe::sim::ScheduledSegment> schedule = pe::sim::scheduleFlight(flight.profile);
  const pe::sim::ScheduledSegment& climb = schedule.at(3);
  const pe::sim::ScheduledSegment& descent = schedule.at(5);
  ASSERT_EQ(climb.segment.kind, pe::sim::SegmentKind::kClimb);
  ASSERT_EQ(descent.segment.kind, pe::sim::SegmentKind::kDescend);
  const pe::sim::PropellerParams& propeller = thesisParams().chain.propeller;
  const HandRotor hand(propeller);
  double lowest = 1.0;
  int climbing = 0, descending = 0;
  for (const pe::sim::TruthSample& truth : flight.sink.truths) {
    const bool in_climb = truth.time_s > climb.start_s + 1.0 && truth.time_s < climb.end_s;
    const bool in_descent = truth.time_s > descent.start_s + 1.0 && truth.time_s < descent.end_s;
    climbing += in_climb;
    descending += in_descent;
    double smallest = truth.motors.front().climb_factor, largest = smallest;
    for (const pe::sim::MotorTruth& motor : truth.motors) {
      smallest = std::min(smallest, motor.climb_factor);
      largest = std::max(largest, motor.climb_factor);
      if (in_climb || in_descent) {
        const double expected = hand.load(motor.rpm * pe::kRadPerSecPerRpm, truth.vertical_speed_m_s, 1.0).thrust;
        ASSERT_NEAR(motor.climb_factor, expected, 0.001) << "t = " << truth.time_s;
      }
      if (in_climb) {
        ASSERT_LT(motor.climb_factor, 0.97) << "t = " << truth.time_s;
      }
      if (in_descent) {
        ASSERT_NEAR(motor.climb_factor, 1.0, 0.02) << "t = " << truth.time_s;
      }
    }
    // The vehicle's factor is the rotors' thrust-weighted mean.
    ASSERT_GE(truth.climb_factor, smallest - 1e-12);
    ASSERT_LE(truth.climb_factor, largest + 1e-12);
    lowest = std::min(lowest, truth.climb_factor);
  }
  EXPECT_GT(climbing, 50);
  EXPECT_GT(descending, 50);
  EXPECT_LT(lowest, 0.96);  // the 1 m/s climbs lose ~5 %
  // The autopilot holds the climb by spinning the rotors faster, which the battery current shows.
  EXPECT_GT(meanCurrent(flight, climb.start_s + 1.0, climb.end_s),
            1.03 * meanCurrent(without, climb.start_s + 1.0, climb.end_s));
}

namespace {

// A flight with a straight leg: take-off, hover, 40 m east at 4 m/s, hover, back, land.
Flight flyMoving(const pe::sim::SimEffects& effects) {
  const std::string text =
      "autopilot: {flavour: px4, pwm_min_us: 1100, pwm_max_us: 1950, disarmed_pwm_us: 900, rc_out_rate_hz: 50}\n"
      "vehicle: {urdf: " + repoPath("config/f450_quad.urdf") +
      ", centre_of_mass_offset_m: [0, 0, 0], landing_gear: {height_m: 0.12, half_width_m: 0.12}, drag_area_m2: 0.04, "
      "battery_initial_soc: 0.95}\n"
      "payload_cable: {length_m: 0.15, attach_point_m: [0, 0, -0.04], stiffness_n_per_m: 1000, damping_n_s_per_m: 10}\n"
      "manifest: {settle_s: 2}\n"
      "segments:\n"
      "  - {type: wait, duration_s: 2}\n"
      "  - {type: takeoff, height_m: 3.0, rate_m_s: 1.5}\n"
      "  - {type: hover, duration_s: 5}\n"
      "  - {type: move, east_m: 40, north_m: 0, speed_m_s: 4}\n"
      "  - {type: hover, duration_s: 5}\n"
      "  - {type: move, east_m: -40, north_m: 0, speed_m_s: 4}\n"
      "  - {type: land, rate_m_s: 0.8}\n";
  Flight flight;
  flight.profile = pe::sim::parseFlightProfileYaml(text, "moving.yaml");
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(flight.profile.vehicle.urdf_path);
  flight.result = pe::sim::simulateFlight(thesisParams(), effects, flight.profile, vehicle, 3, &flight.sink);
  return flight;
}

}  // namespace

TEST(TranslationalLift, MovingRotorsLiftMoreAtTheSameSpeedAndTheMotorsSlowDown) {
  pe::sim::SimEffects effects;
  effects.translational_lift_strength = 1.0;
  const Flight lifted = flyMoving(effects);
  const Flight plain = flyMoving({});
  const std::vector<pe::sim::ScheduledSegment> schedule = pe::sim::scheduleFlight(lifted.profile);
  const pe::sim::ScheduledSegment& leg = schedule.at(3);
  ASSERT_EQ(leg.segment.kind, pe::sim::SegmentKind::kMove);
  // The middle of the first leg, at steady speed: the same speed, less PWM with the lift.
  const auto mean_pwm = [&](const Flight& flight) {
    double sum = 0.0;
    int count = 0;
    for (const pe::sim::TruthSample& truth : flight.sink.truths) {
      if (truth.time_s < leg.start_s + 3.0 || truth.time_s > leg.end_s - 1.0) continue;
      for (const pe::sim::MotorTruth& motor : truth.motors) sum += motor.pwm_us / truth.motors.size();
      ++count;
    }
    return sum / count;
  };
  double speed = 0.0;
  int readings = 0;
  for (const pe::sim::VelocitySample& v : lifted.sink.velocities) {
    if (v.time_s < leg.start_s + 3.0 || v.time_s > leg.end_s - 1.0) continue;
    speed += v.linear_m_s.head<2>().norm();
    ++readings;
  }
  EXPECT_NEAR(speed / readings, 4.0, 0.3);
  // The leg ends where the script says, and the flight lands back at its start.
  ASSERT_FALSE(lifted.sink.poses.empty());
  const pe::sim::PoseSample* settled = &lifted.sink.poses.front();
  for (const pe::sim::PoseSample& pose : lifted.sink.poses) {
    if (std::abs(pose.time_s - (leg.end_s + 4.0)) < std::abs(settled->time_s - (leg.end_s + 4.0))) settled = &pose;
  }
  EXPECT_NEAR(settled->time_s, leg.end_s + 4.0, 0.1);
  EXPECT_NEAR(settled->position_m.x(), 40.0, 1.0);
  EXPECT_LT(lifted.sink.poses.back().position_m.head<2>().norm(), 1.0);
  EXPECT_LT(mean_pwm(lifted), mean_pwm(plain) - 5.0) << mean_pwm(lifted) << " against " << mean_pwm(plain);
}


TEST(EscOffset, ThrustAtXWithOffsetEqualsThrustAtXMinusOffsetWithout) {
  const pe::sim::SimParams params = thesisParams();
  pe::sim::SimEffects effects;
  effects.esc_offset_us = 20.0;
  pe::sim::PowerTrain shifted(pe::sim::PropulsionChain(params.chain), 1, effects, 22.0);
  pe::sim::PowerTrain reference(pe::sim::PropulsionChain(params.chain), 1, {}, 22.0);
  const pe::sim::Supply supply{11.5, 0.015};
  for (double pwm = 1500.0; pwm <= 1800.0; pwm += 0.5) {
    const double a = shifted.step({pwm}, supply, params.bench.air, 0.01).motors[0].thrust_n;
    const double b = reference.step({pwm - 20.0}, supply, params.bench.air, 0.01).motors[0].thrust_n;
    ASSERT_DOUBLE_EQ(a, b) << pwm;
  }
}

TEST(EscOffset, TheAutopilotHoversTheOffsetHigher) {
  pe::sim::SimEffects effects;
  effects.esc_offset_us = 20.0;
  const Flight with = fly(effects);
  const Flight without = fly({});
  for (std::size_t i = 0; i < with.result.segments.size(); ++i) {
    EXPECT_NEAR(meanHoverPwm(with, i) - meanHoverPwm(without, i), 20.0, 2.0) << "segment " << i;
  }
}

// Each ESC's own offset, its gain and its dead band: the duty is the bench ESC's at the pulse
// width moved by the ESC's offset, scaled by the gain, and none within the dead band.
TEST(EscOffset, EachEscItsOwnOffsetGainAndDeadBand) {
  const pe::sim::EscParams esc = thesisParams().chain.esc;
  pe::sim::SimEffects effects;
  effects.esc_offset_us = 10.0;
  effects.esc_offset_per_esc_us = {5.0, -5.0};
  EXPECT_DOUBLE_EQ(pe::sim::escDuty(effects, esc, 0, 1600.0), esc.duty(1600.0, 15.0));
  EXPECT_DOUBLE_EQ(pe::sim::escDuty(effects, esc, 1, 1600.0), esc.duty(1600.0, 5.0));
  effects.esc_gain = 1.05;
  effects.esc_dead_band_us = 8.0;
  const double range = esc.pwm_full_us - esc.pwm_zero_us;
  EXPECT_DOUBLE_EQ(pe::sim::escDuty(effects, esc, 0, 1600.0), 1.05 * (1600.0 - esc.pwm_zero_us - 15.0) / range);
  EXPECT_EQ(pe::sim::escDuty(effects, esc, 0, esc.pwm_zero_us + 15.0 + 7.0), 0.0);
  EXPECT_GT(pe::sim::escDuty(effects, esc, 0, esc.pwm_zero_us + 15.0 + 9.0), 0.0);
  try {
    pe::sim::escDuty(effects, esc, 2, 1600.0);
    FAIL() << "an ESC without an entry was given a duty";
  } catch (const pe::FieldError& e) {
    EXPECT_EQ(e.field(), "esc_offset.per_esc_us");
  }
  const pe::sim::SimParams params = thesisParams();
  EXPECT_THROW(pe::sim::PowerTrain(pe::sim::PropulsionChain(params.chain), 4, effects, 22.0), pe::FieldError);
}

// A loss that follows each rotor's loading: `fraction` at the reference thrust, more above it
// with a positive exponent; the plain law without one.
TEST(ThrustLoss, ALossThatFollowsTheLoading) {
  pe::sim::SimEffects effects;
  EXPECT_EQ(pe::sim::airframeThrustShare(effects, 3.0), 1.0);
  effects.thrust_loss_fraction = 0.05;
  EXPECT_DOUBLE_EQ(pe::sim::airframeThrustShare(effects, 3.0), 0.95);
  effects.thrust_loss_load_exponent = 1.0;
  effects.thrust_loss_reference_thrust_n = 2.0;
  EXPECT_DOUBLE_EQ(pe::sim::airframeThrustShare(effects, 2.0), 0.95);
  EXPECT_DOUBLE_EQ(pe::sim::airframeThrustShare(effects, 4.0), 0.90);
}

// The path's resistance rises with the current drawn through it: at the same pulse width the ESCs
// see less voltage than with the plain law once current flows.
TEST(SupplyResistance, APathThatWarmsWithTheCurrent) {
  const pe::sim::SimParams params = thesisParams();
  pe::sim::SimEffects plain;
  plain.supply_resistance_ohm = 0.05;
  pe::sim::SimEffects warming = plain;
  warming.supply_current_coefficient_per_a = 0.02;
  pe::sim::PowerTrain a(pe::sim::PropulsionChain(params.chain), 4, plain, 22.0);
  pe::sim::PowerTrain b(pe::sim::PropulsionChain(params.chain), 4, warming, 22.0);
  const pe::sim::Supply supply{12.0, 0.015};
  double current = 0.0, esc_a = 0.0, esc_b = 0.0;
  for (int i = 0; i < 300; ++i) {
    const pe::sim::PowerTrainState& sa = a.step({1600.0, 1600.0, 1600.0, 1600.0}, supply, params.bench.air, 0.01);
    esc_a = sa.esc_voltage_v;
    current = sa.current_a;
    esc_b = b.step({1600.0, 1600.0, 1600.0, 1600.0}, supply, params.bench.air, 0.01).esc_voltage_v;
  }
  ASSERT_GT(current, 5.0);
  // The extra drop is about 0.05 ohm x 0.02/A x I^2: tens of millivolts at these currents.
  EXPECT_LT(esc_b, esc_a - 0.5 * 0.05 * 0.02 * current * current);
}

TEST(SimEffects, AllOffByDefaultAndSummarised) {
  EXPECT_EQ(pe::sim::SimEffects{}.summary(), "none");
  pe::sim::SimEffects effects;
  effects.ground_effect_strength = 1.0;
  effects.thrust_loss_fraction = 0.05;
  EXPECT_EQ(effects.summary(), "ground_effect(strength=1) thrust_loss(fraction=0.05)");
  EXPECT_TRUE(pe::sim::rotorInflow({}, 0.12, 0.2, 3.0, 0.0).still());
}
