// Components of the simulator's propulsion chain against their textbook formulas.
#include <gtest/gtest.h>

#include <cmath>

#include "propulsion_estimator/sim/physics/atmosphere.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/sim/physics/lipo_battery.h"
#include "propulsion_estimator/sim/physics/power_train.h"
#include "propulsion_estimator/sim/physics/propulsion_chain.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/common/units.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

constexpr double kPi = 3.14159265358979323846;

pe::sim::SimParams thesisParams() {
  return pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
}

pe::sim::ChainInput inputAt(const pe::sim::SimParams& params, double pwm_us, double voltage_v) {
  return {params.chain.esc.duty(pwm_us), voltage_v, params.bench.air.densityKgM3(),
          params.chain.motor.reference_temperature_c};
}

template <typename F>
std::string refusal(F f) {
  try {
    f();
  } catch (const pe::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(Atmosphere, DensityAndPressureMatchTheStandardAtmosphere) {
  const pe::sim::AirConditions sea_level{15.0, 101325.0};
  EXPECT_NEAR(sea_level.densityKgM3(), 1.2250, 0.0005);             // ISA sea level
  EXPECT_NEAR(sea_level.pressureAtHeightPa(100.0), 100129.0, 5.0);  // ISA at 100 m (with its lapse rate)
  EXPECT_EQ(refusal([] {
              pe::sim::AirConditions{70.0, 101325.0}.validate("air");
            }),
            "air.temperature_c: 70 is outside -40..60 deg C");
  EXPECT_EQ(refusal([] {
              pe::sim::AirConditions{20.0, 12000.0}.validate("air");
            }),
            "air.pressure_pa: 12000 is outside 50000..110000 Pa");
}

TEST(Esc, DutyIsLinearBetweenTheEndPointsAndClamped) {
  const pe::sim::EscParams esc{"e", 1100.0, 1900.0, 0.0};
  EXPECT_DOUBLE_EQ(esc.duty(1500.0), 0.5);
  EXPECT_DOUBLE_EQ(esc.duty(1000.0), 0.0);
  EXPECT_DOUBLE_EQ(esc.duty(2000.0), 1.0);
  EXPECT_DOUBLE_EQ(esc.duty(1520.0, 20.0), 0.5);
  EXPECT_EQ(refusal([] {
              pe::sim::EscParams{"e", 1500.0, 1600.0, 0.0}.validate();
            }),
            "esc.pwm_full_us: 1600 must be at least 200 us above pwm_zero_us (1500)");
}

TEST(BldcMotor, WindingResistanceAndFluxFollowTheirTemperatureCoefficients) {
  pe::sim::BldcMotorParams motor;
  motor.kv_rpm_per_v = 1000.0;
  motor.winding_resistance_ohm = 0.1;
  motor.reference_temperature_c = 25.0;
  motor.flux_temperature_coefficient_per_c = -0.0012;
  const pe::sim::MotorConstants at_reference = pe::sim::motorConstantsAt(motor, 25.0);
  EXPECT_DOUBLE_EQ(at_reference.resistance_ohm, 0.1);
  EXPECT_NEAR(at_reference.torque_constant_nm_per_a, 60.0 / (2.0 * kPi * 1000.0), 1e-12);
  const pe::sim::MotorConstants hot = pe::sim::motorConstantsAt(motor, 65.0);
  // Copper: R(T) proportional to 1 + 0.00393 (T - 20 C).
  EXPECT_NEAR(hot.resistance_ohm, 0.1 * (1.0 + 0.00393 * 45.0) / (1.0 + 0.00393 * 5.0), 1e-12);
  EXPECT_NEAR(hot.torque_constant_nm_per_a / at_reference.torque_constant_nm_per_a, 1.0 - 0.0012 * 40.0, 1e-12);
}

TEST(BldcMotor, ThermalModelIsAFirstOrderLagToAirPlusHeatTimesResistance) {
  pe::sim::BldcMotorParams motor;
  motor.thermal_capacity_j_per_c = 30.0;
  // 10 W through 2 C/W settles 20 C above the air with a 60 s time constant.
  EXPECT_NEAR(pe::sim::nextWindingTemperature(motor, 20.0, 10.0, 20.0, 2.0, 60.0), 20.0 + 20.0 * (1.0 - std::exp(-1.0)),
              1e-12);
  EXPECT_NEAR(pe::sim::nextWindingTemperature(motor, 20.0, 10.0, 20.0, 2.0, 1e6), 40.0, 1e-9);
}

TEST(Propeller, ThrustAndTorqueFollowTheCoefficientLaws) {
  const pe::sim::PropellerParams propeller{"p", 0.25, 0.1, 0.005, 0.0};
  EXPECT_NEAR(propeller.thrustN(1.2, 100.0), 0.1 * 1.2 * 1e4 * std::pow(0.25, 4), 1e-12);
  EXPECT_NEAR(propeller.torqueNm(1.2, 100.0), 0.005 * 1.2 * 1e4 * std::pow(0.25, 5), 1e-12);
}

TEST(Propeller, AScaledPropellerMakesTheThrustFactorAndLessTorqueLikeASmallerOne) {
  // Geometrically similar, diameter x 0.85^(1/4): T ~ D^4 gives 0.85 of the thrust at the same
  // speed, Q ~ D^5 gives 0.85^(5/4) = 0.816 of the torque.
  const pe::sim::PropellerParams intact = thesisParams().chain.propeller;
  const pe::sim::PropellerParams weak = pe::sim::scaledPropeller(intact, 0.85);
  EXPECT_NEAR(weak.diameter_m, intact.diameter_m * std::pow(0.85, 0.25), 1e-15);
  EXPECT_NEAR(weak.thrustN(1.2, 100.0), 0.85 * intact.thrustN(1.2, 100.0), 1e-12);
  EXPECT_NEAR(weak.torqueNm(1.2, 100.0), std::pow(0.85, 1.25) * intact.torqueNm(1.2, 100.0), 1e-12);
  EXPECT_NEAR(std::pow(0.85, 1.25), 0.816, 0.001);
  EXPECT_NEAR(weak.inertia_kg_m2, std::pow(0.85, 1.25) * intact.inertia_kg_m2, 1e-18);
  EXPECT_EQ(weak.thrust_coefficient, intact.thrust_coefficient);
  EXPECT_EQ(weak.torque_coefficient, intact.torque_coefficient);
  EXPECT_EQ(weak.solidity, intact.solidity);
}

TEST(PropulsionChain, SteadyStateBalancesTorqueAndVoltage) {
  const pe::sim::SimParams params = thesisParams();
  const pe::sim::PropulsionChain chain(params.chain);
  const pe::sim::MotorConstants motor =
      pe::sim::motorConstantsAt(params.chain.motor, params.chain.motor.reference_temperature_c);
  const double resistance = motor.resistance_ohm + params.chain.esc.resistance_ohm;
  for (double pwm : {1300.0, 1600.0, 1900.0}) {
    const pe::sim::ChainInput input = inputAt(params, pwm, 11.1);
    const pe::sim::ChainState state = chain.steady(input);
    ASSERT_GT(state.omega_rad_s, 0.0);
    // Kt (I - I0) = CQ rho n^2 D^5 and duty V = Kt w + R I.
    EXPECT_NEAR(motor.torque_constant_nm_per_a * (state.motor_current_a - motor.no_load_current_a), state.torque_nm,
                1e-9);
    EXPECT_NEAR(input.duty * 11.1,
                motor.torque_constant_nm_per_a * state.omega_rad_s + resistance * state.motor_current_a, 1e-9);
    EXPECT_NEAR(state.input_current_a, input.duty * state.motor_current_a, 1e-12);
    EXPECT_NEAR(state.input_power_w, 11.1 * state.input_current_a, 1e-9);
    const double n = state.omega_rad_s / (2.0 * kPi);
    EXPECT_NEAR(state.thrust_n,
                params.chain.propeller.thrust_coefficient * input.air_density_kg_m3 * n * n * std::pow(0.2388, 4),
                1e-9);
    EXPECT_NEAR(state.heat_w,
                state.motor_current_a * state.motor_current_a * motor.resistance_ohm +
                    motor.no_load_current_a * motor.torque_constant_nm_per_a * state.omega_rad_s,
                1e-9);
  }
}

TEST(PropulsionChain, StandsBelowTheVoltageThatOvercomesTheNoLoadCurrent) {
  const pe::sim::SimParams params = thesisParams();
  const pe::sim::PropulsionChain chain(params.chain);
  const pe::sim::MotorConstants motor =
      pe::sim::motorConstantsAt(params.chain.motor, params.chain.motor.reference_temperature_c);
  const double resistance = motor.resistance_ohm + params.chain.esc.resistance_ohm;
  // duty V / R just below I0.
  const double duty = 0.99 * motor.no_load_current_a * resistance / 12.0;
  const pe::sim::ChainState state = chain.steady({duty, 12.0, 1.2, params.chain.motor.reference_temperature_c});
  EXPECT_EQ(state.omega_rad_s, 0.0);
  EXPECT_NEAR(state.motor_current_a, duty * 12.0 / resistance, 1e-12);
  EXPECT_EQ(chain.steady({0.0, 12.0, 1.2, 25.0}).input_current_a, 0.0);
}

TEST(PropulsionChain, SpeedTimeConstantIsInertiaOverTorqueSlope) {
  const pe::sim::SimParams params = thesisParams();
  const pe::sim::PropulsionChain chain(params.chain);
  const pe::sim::ChainInput input = inputAt(params, 1650.0, 11.5);
  const double omega = chain.steady(input).omega_rad_s;
  const pe::sim::MotorConstants motor = pe::sim::motorConstantsAt(params.chain.motor, input.winding_temperature_c);
  // Net torque on the rotor at speed w, differentiated numerically.
  const auto net = [&](double w) {
    const pe::sim::ChainState state = chain.atSpeed(input, w);
    return motor.torque_constant_nm_per_a * (state.motor_current_a - motor.no_load_current_a) - state.torque_nm;
  };
  const double slope = (net(omega + 1e-3) - net(omega - 1e-3)) / 2e-3;
  EXPECT_NEAR(chain.speedTimeConstantS(input, omega), chain.inertiaKgM2() / -slope, 1e-9);
  EXPECT_GT(chain.speedTimeConstantS(input, omega), 0.03);  // a 9.4 in propeller takes tens of ms
  EXPECT_LT(chain.speedTimeConstantS(input, omega), 0.2);
}

TEST(PowerTrain, RotorSpeedFollowsAFirstOrderLagToTheSteadyState) {
  const pe::sim::SimParams params = thesisParams();
  pe::sim::PowerTrain train(pe::sim::PropulsionChain(params.chain), 1, {}, 22.0);
  const pe::sim::Supply supply{12.0, 0.0};
  const pe::sim::AirConditions air = params.bench.air;
  for (int i = 0; i < 2000; ++i) train.step({1500.0}, supply, air, 1e-3);
  const double start = train.step({1600.0}, supply, air, 0.0).motors[0].omega_rad_s;
  const pe::sim::ChainInput input = inputAt(params, 1600.0, 12.0);
  const double target = train.chain().steady(input).omega_rad_s;
  const double tau = train.chain().speedTimeConstantS(input, target);
  const int steps = 1000;
  for (int i = 0; i < steps; ++i) train.step({1600.0}, supply, air, tau / steps);
  const double after_tau = train.step({1600.0}, supply, air, 0.0).motors[0].omega_rad_s;
  // exp(-1) of the step remains after one time constant (tau varies a little along the way).
  EXPECT_NEAR((target - after_tau) / (target - start), std::exp(-1.0), 0.02);
  for (int i = 0; i < 2000; ++i) train.step({1600.0}, supply, air, 1e-3);
  EXPECT_NEAR(train.step({1600.0}, supply, air, 0.0).motors[0].omega_rad_s, target, 1e-6 * target);
}

TEST(PowerTrain, SettlesOnTheSteadyStateOfMotorsSharingASupply) {
  // Four motors on a battery (EMF 12 V behind 15 mOhm) through a 50 mOhm path.
  const pe::sim::SimParams params = thesisParams();
  pe::sim::SimEffects effects;
  effects.supply_resistance_ohm = 0.05;
  pe::sim::PowerTrain train(pe::sim::PropulsionChain(params.chain), 4, effects, 22.0);
  const pe::sim::Supply supply{12.0, 0.015};
  const std::vector<double> pwm(4, 1650.0);
  for (int i = 0; i < 3000; ++i) train.step(pwm, supply, params.bench.air, 1e-3);
  const pe::sim::PowerTrainState& state = train.step(pwm, supply, params.bench.air, 0.0);
  double esc_voltage = 0.0;
  const pe::sim::ChainState steady =
      train.chain().steadyFromSource(inputAt(params, 1650.0, 0.0), 12.0, 0.065, 4, &esc_voltage);
  EXPECT_NEAR(state.esc_voltage_v, esc_voltage, 1e-6);
  EXPECT_NEAR(state.esc_voltage_v, 12.0 - 0.065 * 4.0 * steady.input_current_a, 1e-6);
  EXPECT_NEAR(state.terminal_voltage_v, 12.0 - 0.015 * state.current_a, 1e-9);
  for (const pe::sim::ChainState& motor : state.motors) EXPECT_NEAR(motor.thrust_n, steady.thrust_n, 1e-6);
}

TEST(PowerTrain, AStepOfNoTimeOnlyEvaluatesTheState) {
  // The bench reads the state after a dwell with dt = 0: the rotor and the windings must stay put,
  // with the temperature-coupled motor as well.
  const pe::sim::SimParams params = thesisParams();
  pe::sim::SimEffects effects;
  effects.motor_thermal_resistance_c_per_w = 2.0;
  pe::sim::PowerTrain train(pe::sim::PropulsionChain(params.chain), 1, effects, 22.0);
  const pe::sim::Supply supply{12.0, 0.015};
  for (int i = 0; i < 500; ++i) train.step({1700.0}, supply, params.bench.air, 1e-3);
  const pe::sim::PowerTrainState before = train.step({1700.0}, supply, params.bench.air, 0.0);
  const pe::sim::PowerTrainState again = train.step({1700.0}, supply, params.bench.air, 0.0);
  EXPECT_EQ(again.motors[0].omega_rad_s, before.motors[0].omega_rad_s);
  EXPECT_EQ(again.winding_temperature_c[0], before.winding_temperature_c[0]);
  EXPECT_EQ(again.current_a, before.current_a);
  EXPECT_GT(train.step({1700.0}, supply, params.bench.air, 0.0).motors[0].omega_rad_s, 0.0);
}

TEST(PowerTrain, AMotorWhoseEscIsOffCoastsWithoutCurrent) {
  const pe::sim::SimParams params = thesisParams();
  pe::sim::PowerTrain train(pe::sim::PropulsionChain(params.chain), 1, {}, 22.0);
  const pe::sim::Supply supply{12.0, 0.0};
  for (int i = 0; i < 2000; ++i) train.step({1600.0}, supply, params.bench.air, 1e-3);
  const double spinning = train.step({900.0}, supply, params.bench.air, 0.0).motors[0].omega_rad_s;
  double previous = spinning;
  for (int i = 0; i < 200; ++i) {
    const pe::sim::PowerTrainState& state = train.step({900.0}, supply, params.bench.air, 1e-3);
    EXPECT_EQ(state.current_a, 0.0);
    EXPECT_LE(state.motors[0].omega_rad_s, previous);
    previous = state.motors[0].omega_rad_s;
  }
  EXPECT_LT(previous, 0.8 * spinning);
}

TEST(LipoBattery, OpenCircuitVoltageInterpolatesTheTable) {
  const pe::sim::LipoBatteryParams battery = thesisParams().battery;
  EXPECT_NEAR(battery.openCircuitVoltage(1.0), 12.6, 1e-12);
  EXPECT_NEAR(battery.openCircuitVoltage(0.5), 3 * 3.84, 1e-12);
  EXPECT_NEAR(battery.openCircuitVoltage(0.55), 3 * (3.84 + 0.5 * (3.87 - 3.84)), 1e-12);
  EXPECT_NEAR(battery.openCircuitVoltage(-0.1), 3 * 3.27, 1e-12);
}

TEST(LipoBattery, CountsChargeAndPolarisesLikeAnRcPair) {
  const pe::sim::LipoBatteryParams params = thesisParams().battery;
  pe::sim::LipoBattery battery(params, 1.0);
  const double tau = params.rc_resistance_ohm * params.rc_capacitance_f;
  battery.draw(10.0, tau);
  EXPECT_NEAR(battery.polarisationVoltage(), 10.0 * params.rc_resistance_ohm * (1.0 - std::exp(-1.0)), 1e-12);
  EXPECT_NEAR(battery.stateOfCharge(), 1.0 - 10.0 * tau / (params.capacity_ah * 3600.0), 1e-12);
  EXPECT_NEAR(battery.terminalVoltage(10.0),
              params.openCircuitVoltage(battery.stateOfCharge()) - battery.polarisationVoltage() -
                  10.0 * params.series_resistance_ohm,
              1e-12);
  pe::sim::LipoBattery full(params, 1.0);
  full.draw(params.capacity_ah, 3600.0);  // the rated capacity in one hour
  EXPECT_NEAR(full.stateOfCharge(), 0.0, 1e-12);
  EXPECT_EQ(refusal([&] { pe::sim::LipoBattery(params, 1.2); }), "initial_soc: 1.2 is outside 0..1");
}
