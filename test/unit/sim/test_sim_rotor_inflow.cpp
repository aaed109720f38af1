// The rotor's thrust and torque in its inflow (rotor_inflow.h) against blade-element momentum
// theory worked by hand: the same relations solved here by another method (damped fixed-point
// iteration on C_T instead of bisection on sqrt(C_T / 2)), their first-order forms, the numbers
// they give the thesis' DJI 9443, and the motor's operating point that follows.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/sim/physics/power_train.h"
#include "propulsion_estimator/sim/physics/rotor_inflow.h"
#include "propulsion_estimator/sim/physics/sim_params_yaml.h"
#include "hand_rotor.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

// Near the thesis quad's hover speed (6080 rpm).
constexpr double kOmega = 640.0;

pe::sim::SimParams thesisParams() { return pe::sim::loadSimParamsFile(repoPath("config/sim/e300_dji2212_dji9443.yaml")); }

pe::sim::PropellerParams withSolidity(double solidity) {
  pe::sim::PropellerParams propeller = thesisParams().chain.propeller;
  propeller.solidity = solidity;
  return propeller;
}

}  // namespace

TEST(RotorAerodynamics, StillAirOutOfGroundEffectGivesTheStaticCoefficientsExactly) {
  const pe::sim::RotorAerodynamics rotor(thesisParams().chain.propeller);
  for (double omega : {0.0, 100.0, kOmega, 1000.0}) {
    const pe::sim::RotorLoad load = rotor.load(omega, {});
    EXPECT_EQ(load.thrust, 1.0);
    EXPECT_EQ(load.torque, 1.0);
  }
  // And continuously so: the calibration puts hover at the root of the blade equation.
  const pe::sim::RotorLoad nearly = rotor.load(kOmega, {1e-9, 1.0 - 1e-12});
  EXPECT_NEAR(nearly.thrust, 1.0, 1e-9);
  EXPECT_NEAR(nearly.torque, 1.0, 1e-9);
}

TEST(RotorAerodynamics, MatchesBladeElementMomentumTheoryWorkedByHand) {
  const pe::sim::PropellerParams propeller = thesisParams().chain.propeller;
  const pe::sim::RotorAerodynamics rotor(propeller);
  const HandRotor hand(propeller);
  const double radius = propeller.radiusM();
  for (double z : {radius / 2.0, radius, 0.235, 4.0 * radius}) {
    const double ground = 1.0 - std::pow(radius / (4.0 * z), 2);
    for (double axial : {2.0, 1.0, 0.1, 0.0, -0.1, -0.8, -3.0, -8.0}) {
      const pe::sim::RotorLoad load = rotor.load(kOmega, {axial, ground});
      const pe::sim::RotorLoad expected = hand.load(kOmega, axial, ground);
      EXPECT_NEAR(load.thrust, expected.thrust, 1e-9) << z << " m, " << axial << " m/s";
      EXPECT_NEAR(load.torque, expected.torque, 1e-9) << z << " m, " << axial << " m/s";
    }
  }
  // The DJI 9443 at 640 rad/s (hand values of the relations above): 1 m/s of climb costs 4.8 % of
  // the thrust and 0.27 % of the torque; the 0.8 m/s descent of the default flight gains 0.34 %
  // of thrust; the ground at 0.235 m (the 0.2 m hover) gives 1.1 %, not Cheeseman-Bennett's 1.6 %.
  EXPECT_NEAR(rotor.load(kOmega, {1.0, 1.0}).thrust, 0.95185, 1e-5);
  EXPECT_NEAR(rotor.load(kOmega, {1.0, 1.0}).torque, 0.99733, 1e-5);
  EXPECT_NEAR(rotor.load(kOmega, {-0.8, 1.0}).thrust, 1.00340, 1e-5);
  EXPECT_NEAR(rotor.load(kOmega, {0.0, 1.0 / pe::sim::groundEffectFactor(radius, 0.235, 1.0)}).thrust, 1.01102, 1e-5);
}

TEST(RotorAerodynamics, EdgewiseFlowGivesTranslationalLiftAsGlauertsMomentumTheory) {
  const pe::sim::PropellerParams propeller = thesisParams().chain.propeller;
  const pe::sim::RotorAerodynamics rotor(propeller);
  const HandRotor hand(propeller);
  double previous = 1.0;
  for (double edgewise : {0.5, 1.0, 2.0, 3.0, 5.0, 8.0}) {
    pe::sim::RotorInflow inflow;
    inflow.edgewise_speed_m_s = edgewise;
    const pe::sim::RotorLoad load = rotor.load(kOmega, inflow);
    const pe::sim::RotorLoad expected = hand.loadEdgewise(kOmega, edgewise);
    EXPECT_NEAR(load.thrust, expected.thrust, 1e-9) << edgewise << " m/s";
    EXPECT_NEAR(load.torque, expected.torque, 1e-9) << edgewise << " m/s";
    // At a fixed speed, more air through the disc: more thrust the faster it moves.
    EXPECT_GT(load.thrust, previous) << edgewise << " m/s";
    previous = load.thrust;
  }
  pe::sim::RotorInflow three;
  three.edgewise_speed_m_s = 3.0;
  // The DJI 9443 at 640 rad/s, 3 m/s edgewise (printed once by this test): a few % of thrust.
  std::printf("translational lift at 3 m/s: thrust x %.4f, torque x %.4f\n", rotor.load(kOmega, three).thrust,
              rotor.load(kOmega, three).torque);
  EXPECT_GT(rotor.load(kOmega, three).thrust, 1.02);
}

TEST(RotorAerodynamics, GroundEffectRaisesThrustByTheFirstOrderShareOfCheesemanBennett) {
  // G = 1 - eps lowers the inflow; to first order dT/T = lambda_0 / (Theta - lambda_0 / 2) eps, a
  // share of Cheeseman-Bennett's equal-power gain eps. The torque moves by k (Theta - 2 lambda_0)
  // d lambda, which for the DJI 9443 (Theta ~ 2 lambda_0) is nearly nothing.
  const pe::sim::PropellerParams propeller = thesisParams().chain.propeller;
  const pe::sim::RotorAerodynamics rotor(propeller);
  const HandRotor hand(propeller);
  const double share = hand.lambda0 / (hand.theta - hand.lambda0 / 2.0);
  EXPECT_NEAR(share, 0.679, 0.001);
  const double eps = 1e-3;
  const pe::sim::RotorLoad small = rotor.load(kOmega, {0.0, 1.0 - eps});
  EXPECT_NEAR((small.thrust - 1.0) / eps, share, 0.002 * share);
  EXPECT_LT(std::fabs(small.torque - 1.0), 0.02 * eps);
  // Down to half a radius the thrust keeps rising and the torque stays within 2.5 %.
  double previous = 1.0;
  for (double z : {4.0, 2.0, 1.0, 0.5}) {
    const double eps_z = std::pow(1.0 / (4.0 * z), 2);
    const pe::sim::RotorLoad load = rotor.load(kOmega, {0.0, 1.0 - eps_z});
    EXPECT_GT(load.thrust, previous) << z;
    EXPECT_LT(load.thrust, 1.0 + eps_z) << z;  // below Cheeseman-Bennett's equal-power ratio
    EXPECT_NEAR(load.torque, 1.0, 0.025) << z;
    previous = load.thrust;
  }
}

TEST(RotorAerodynamics, ClimbLowersThrustWhileASlowDescentHardlyRaisesIt) {
  // First order in lambda_c = v / (Omega R): a climb dT/T = -(1 - kappa/2) / (Theta - lambda_0/2)
  // lambda_c (the induced inflow gives back kappa/2 of it); a descent -(1 + k1) / (Theta -
  // lambda_0/2) lambda_c with k1 = -1.125 the slope of the measured curve: the induced inflow rises
  // about as fast as the rotor descends.
  const pe::sim::PropellerParams propeller = thesisParams().chain.propeller;
  const pe::sim::RotorAerodynamics rotor(propeller);
  const HandRotor hand(propeller);
  const double tip_speed = kOmega * propeller.radiusM();
  const double denominator = hand.theta - hand.lambda0 / 2.0;
  const double v = 0.01;
  EXPECT_NEAR((1.0 - rotor.load(kOmega, {v, 1.0}).thrust) / (v / tip_speed), (1.0 - 1.15 / 2.0) / denominator,
              0.01 * (1.0 - 1.15 / 2.0) / denominator);
  EXPECT_NEAR((rotor.load(kOmega, {-v, 1.0}).thrust - 1.0) / (-v / tip_speed), -(1.0 - 1.125) / denominator,
              0.05 * 0.125 / denominator);
  double previous = 1.0;
  for (double climb : {0.5, 1.0, 2.0, 3.0}) {
    const double thrust = rotor.load(kOmega, {climb, 1.0}).thrust;
    EXPECT_LT(thrust, previous) << climb;
    previous = thrust;
  }
  for (double descent : {-0.5, -0.8, -1.0}) EXPECT_NEAR(rotor.load(kOmega, {descent, 1.0}).thrust, 1.0, 0.01);
  EXPECT_GT(rotor.load(kOmega, {-3.0, 1.0}).thrust, 1.05);
  // The same speed is a smaller inflow ratio for a faster rotor.
  EXPECT_LT(rotor.load(2.0 * kOmega, {1.0, 1.0}).thrust - 1.0, 0.0);
  EXPECT_GT(rotor.load(2.0 * kOmega, {1.0, 1.0}).thrust, rotor.load(kOmega, {1.0, 1.0}).thrust);
}

TEST(RotorAerodynamics, TheTorqueFollowsTheSignOfTheBladeLoading) {
  // The induced torque k lambda (Theta - lambda) peaks at lambda = Theta / 2. A lightly loaded
  // blade (low solidity: Theta > 2 lambda_0) loses torque when the ground lowers the inflow and
  // gains it in a climb; a heavily loaded one does the opposite.
  const double radius = thesisParams().chain.propeller.radiusM();
  const double ground = 1.0 - std::pow(radius / (4.0 * radius), 2);
  const HandRotor light_hand(withSolidity(0.05));
  const HandRotor heavy_hand(withSolidity(0.15));
  ASSERT_GT(light_hand.theta, 2.0 * light_hand.lambda0);
  ASSERT_LT(heavy_hand.theta, 2.0 * heavy_hand.lambda0);
  const pe::sim::RotorAerodynamics light(withSolidity(0.05));
  const pe::sim::RotorAerodynamics heavy(withSolidity(0.15));
  EXPECT_LT(light.load(kOmega, {0.0, ground}).torque, 0.99);
  EXPECT_GT(light.load(kOmega, {1.0, 1.0}).torque, 1.005);
  EXPECT_GT(heavy.load(kOmega, {0.0, ground}).torque, 1.005);
  EXPECT_LT(heavy.load(kOmega, {1.0, 1.0}).torque, 0.99);
}

TEST(RotorAerodynamics, TheMotorsOperatingPointAnswersTheRotorsTorque) {
  // At a fixed pulse width the power train settles where the motor's torque Kt (I - I0) meets the
  // propeller's static torque times the load factor at the settled speed. A lightly loaded blade
  // in ground effect needs less torque: the rotor speeds up and draws less current; a heavily
  // loaded one slows down and draws more.
  const pe::sim::SimParams params = thesisParams();
  const double radius = params.chain.propeller.radiusM();
  const pe::sim::RotorInflow ground{0.0, 1.0 - std::pow(radius / (4.0 * radius), 2)};
  const pe::sim::Supply supply{12.0, 0.0};
  const auto settle = [&](double solidity, const pe::sim::RotorInflow& inflow) {
    pe::sim::ChainParams chain = params.chain;
    chain.propeller.solidity = solidity;
    pe::sim::PowerTrain train(pe::sim::PropulsionChain(chain), 1, {}, 22.0);
    train.setInflow(0, inflow);
    for (int i = 0; i < 3000; ++i) train.step({1650.0}, supply, params.bench.air, 1e-3);
    return train.step({1650.0}, supply, params.bench.air, 0.0).motors[0];
  };
  const pe::sim::MotorConstants motor = pe::sim::motorConstantsAt(params.chain.motor, params.chain.motor.reference_temperature_c);
  for (double solidity : {0.05, 0.15}) {
    const pe::sim::ChainState still = settle(solidity, {});
    const pe::sim::ChainState near_ground = settle(solidity, ground);
    const pe::sim::RotorLoad load = pe::sim::RotorAerodynamics(withSolidity(solidity)).load(near_ground.omega_rad_s, ground);
    const double torque = params.chain.propeller.torqueNm(params.bench.air.densityKgM3(),
                                                          near_ground.omega_rad_s / pe::kTwoPi) * load.torque;
    EXPECT_NEAR(motor.torque_constant_nm_per_a * (near_ground.motor_current_a - motor.no_load_current_a), torque,
                1e-6 * torque) << solidity;
    EXPECT_NEAR(near_ground.torque_nm, torque, 1e-12) << solidity;
    if (solidity < 0.1) {
      EXPECT_GT(near_ground.omega_rad_s, still.omega_rad_s + 1.0);
      EXPECT_LT(near_ground.input_current_a, 0.99 * still.input_current_a);
    } else {
      EXPECT_LT(near_ground.omega_rad_s, still.omega_rad_s - 1.0);
      EXPECT_GT(near_ground.input_current_a, 1.01 * still.input_current_a);
    }
    EXPECT_GT(near_ground.thrust_n, 1.02 * still.thrust_n) << solidity;
  }
}
