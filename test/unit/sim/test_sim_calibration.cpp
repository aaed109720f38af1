// The default simulator parameters against the thesis' numbers: the bench maxima (tables 7.1-7.3,
// 7.6), the response surfaces of chapter 5 over the hover band, the motor temperature of table
// 7.7, and the hover of the 1.315 kg quad of chapter 6.
#include <gtest/gtest.h>

#include <cmath>

#include "propulsion_estimator/sim/stand/bench_simulator.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/sim/physics/propulsion_chain.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

pe::sim::SimParams thesisParams() {
  return pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml"));
}

// The noise-free bench row at `pwm_us` of a constant-voltage sweep at `voltage_v`.
std::size_t rowAt(const pe::BenchLog& log, double pwm_us) {
  const auto& pwm = log.column(pe::BenchColumn::kPwm);
  for (std::size_t i = 0; i < pwm.size(); ++i) {
    if (std::fabs(pwm[i] - pwm_us) < 1e-9) return i;
  }
  ADD_FAILURE() << "no row at " << pwm_us << " us";
  return 0;
}

void expectBenchMaxima(const pe::sim::SimParams& params, double pwm_us, double thrust_g, double current_a,
                       double power_w, double rpm) {
  pe::sim::BenchExperiment sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.voltages_v = {12.6};
  pe::BenchLog truth;
  pe::sim::simulateBench(params, {}, sweep, 1, &truth);
  const std::size_t row = rowAt(truth, pwm_us);
  EXPECT_NEAR(truth.column(pe::BenchColumn::kThrust)[row] / pe::kNewtonPerGramForce, thrust_g, 0.10 * thrust_g);
  EXPECT_NEAR(truth.column(pe::BenchColumn::kCurrent)[row], current_a, 0.10 * current_a);
  EXPECT_NEAR(truth.column(pe::BenchColumn::kPower)[row], power_w, 0.10 * power_w);
  EXPECT_NEAR(truth.column(pe::BenchColumn::kRpm)[row], rpm, 0.10 * rpm);
}

}  // namespace

TEST(SimCalibration, E300Dji2212Dji9443MeetsTheThesisMaximaWithinTenPercent) {
  // Tables 7.1, 7.2, 7.3, 7.6 (9443 column, E300-2212 row) at 12.6 V and 1900 us.
  expectBenchMaxima(thesisParams(), 1900.0, 681.85, 8.89, 112.12, 8682.0);
}

TEST(SimCalibration, Dji430LiteDji2312eDji9450MeetsTheThesisMaximaWithinTenPercent) {
  // Tables 7.1, 7.2, 7.3, 7.6 (9450 column, 430LITE-2312E row) at 12.6 V and 1800 us.
  expectBenchMaxima(pe::sim::loadSimParamsFile(repoPath("config/sim/430lite_dji2312e_dji9450.yaml")), 1800.0, 734.11,
                    10.35, 129.09, 7602.0);
}

TEST(SimCalibration, MatchesTheThesisSurfacesOverTheHoverBand) {
  // The estimator is tested on simulated flights with the thesis' surfaces: over the band a
  // hovering quad uses, physics and surfaces must agree to a few percent.
  const pe::sim::SimParams params = thesisParams();
  const pe::sim::PropulsionChain chain(params.chain);
  const pe::PropulsionModel surfaces = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  const double density = params.bench.air.densityKgM3();
  double worst_thrust = 0.0, worst_rpm = 0.0, worst_current = 0.0;
  for (double pwm = 1550.0; pwm <= 1800.0; pwm += 10.0) {
    for (double voltage = 10.5; voltage <= 12.6 + 1e-9; voltage += 0.1) {
      const pe::sim::ChainState state =
          chain.steady({params.chain.esc.duty(pwm), voltage, density, params.chain.motor.reference_temperature_c});
      pe::OperatingPoint surface;
      surfaces.evaluate(pwm, voltage, &surface);
      worst_thrust = std::max(worst_thrust, std::fabs(state.thrust_n / surface.thrust_n - 1.0));
      worst_rpm = std::max(worst_rpm, std::fabs(state.rpm() / surface.rpm - 1.0));
      worst_current = std::max(worst_current, std::fabs(state.input_current_a / surface.current_a - 1.0));
    }
  }
  EXPECT_LT(worst_thrust, 0.05);
  EXPECT_LT(worst_rpm, 0.05);
  EXPECT_LT(worst_current, 0.05);
}

TEST(SimCalibration, MotorTemperatureAtTheEndOfTheSweepMatchesTable77) {
  // 33.63 deg C after the 1200-1900 us sweep at 12.6 V from a 22 deg C room (1 s per step).
  const pe::sim::SimParams params = thesisParams();
  pe::sim::BenchExperiment sweep = pe::sim::thesisBenchExperiment(pe::sim::BenchExperimentKind::kPwmSweep, params);
  sweep.voltages_v = {12.6};
  pe::BenchLog truth;
  pe::sim::simulateBench(params, {}, sweep, 1, &truth);
  EXPECT_NEAR(truth.column(pe::BenchColumn::kMotorTemp).back(), 33.63, 1.0);
}

TEST(SimCalibration, TheThesisQuadHoversBetween1600And1750Us) {
  // 1.315 kg (table 6.2) on four rotors fed from the 3S pack through its series resistance, from
  // a full (12.6 V) to an empty (10.5 V) battery.
  const pe::sim::SimParams params = thesisParams();
  const pe::sim::PropulsionChain chain(params.chain);
  const pe::Vehicle quad = pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf"));
  ASSERT_TRUE(quad.empty_mass);
  ASSERT_NEAR(quad.empty_mass->mass_kg, 1.315, 1e-9);
  const double per_rotor_n = quad.empty_mass->mass_kg * pe::kStandardGravity / 4.0;
  for (double source_v : {12.6, 11.1, 10.5}) {
    double lo = 1200.0, hi = 1950.0;
    while (hi - lo > 0.01) {
      const double pwm = 0.5 * (lo + hi);
      const pe::sim::ChainInput input{params.chain.esc.duty(pwm), 0.0, params.bench.air.densityKgM3(),
                                      params.chain.motor.reference_temperature_c};
      const double thrust =
          chain.steadyFromSource(input, source_v, params.battery.series_resistance_ohm, 4, nullptr).thrust_n;
      (thrust < per_rotor_n ? lo : hi) = pwm;
    }
    EXPECT_GT(lo, 1600.0) << source_v << " V";
    EXPECT_LT(lo, 1750.0) << source_v << " V";
  }
}

TEST(SimCalibration, BothPropellersHaveTheFigureOfMeritOfASmallRotor) {
  // Momentum theory: ideal hover power T^1.5 / sqrt(2 rho A), A = pi D^2 / 4. With T = CT rho n^2 D^4
  // and P = CP rho n^3 D^5 (CP = 2 pi CQ) the figure of merit is CT^1.5 sqrt(2 / pi) / CP; small
  // fixed-pitch rotors reach 0.5-0.7 (the 9443's parameter file quotes its 0.65).
  const double pi = 3.14159265358979323846;
  const auto figureOfMerit = [pi](const pe::sim::PropellerParams& propeller) {
    return std::pow(propeller.thrust_coefficient, 1.5) * std::sqrt(2.0 / pi) / (2.0 * pi * propeller.torque_coefficient);
  };
  EXPECT_NEAR(figureOfMerit(thesisParams().chain.propeller), 0.65, 0.005);
  EXPECT_NEAR(
      figureOfMerit(pe::sim::loadSimParamsFile(repoPath("config/sim/430lite_dji2312e_dji9450.yaml")).chain.propeller),
      0.64, 0.005);
}
