#include <gtest/gtest.h>

#include <random>

#include <Eigen/Dense>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/estimation/motor_change.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace pe = propulsion_estimator;

namespace {

// A quad X whose rotors differ as real ones do: each rotor's thrust over the model's at its PWM
// (part-to-part, a few per cent) and drag torque per thrust (clockwise and counter-clockwise
// propellers that are not mirror images), drawn once per vehicle.
struct Quad {
  pe::Vehicle vehicle = pe::Vehicle::quadX(0.225);
  std::array<double, 4> thrust_factor{};
  std::array<double, 4> torque_per_thrust{};

  explicit Quad(unsigned seed) {
    std::mt19937 random(seed);
    std::normal_distribution<double> part(0.0, 0.03);
    for (int k = 0; k < 4; ++k) {
      thrust_factor[k] = 1.0 + part(random);
      // One spin direction's propellers turn 8 % more thrust into torque than the other's.
      torque_per_thrust[k] = (vehicle.rotors[k].spin_direction > 0 ? 1.04 : 0.96) * (1.0 + part(random));
    }
  }

  // One flight's mean model thrust per motor in steady hover (N): the thrusts that balance weight,
  // roll, pitch and yaw about a centre of gravity `cg_m` off the origin, read back through each
  // rotor's factor, with `noise` relative scatter on each motor's mean.
  pe::HoverThrusts hover(const Eigen::Vector2d& cg_m, std::mt19937& random, double noise = 0.003) const {
    Eigen::Matrix4d a;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d arm = vehicle.rotors[k].position_m.head<2>() - cg_m;
      a.col(k) << 1.0, arm.x(), arm.y(), vehicle.rotors[k].spin_direction * torque_per_thrust[k];
    }
    const Eigen::Vector4d thrust = a.colPivHouseholderQr().solve(Eigen::Vector4d(15.0, 0.0, 0.0, 0.0));
    std::normal_distribution<double> scatter(0.0, noise);
    pe::HoverThrusts model(4);
    for (int k = 0; k < 4; ++k) model[k] = thrust[k] / thrust_factor[k] * (1.0 + scatter(random));
    return model;
  }

  // Flights whose centre of gravity wanders by `cg_spread_m` (a battery seated differently).
  std::vector<pe::HoverThrusts> flights(int count, std::mt19937& random, double cg_spread_m = 0.001) const {
    std::normal_distribution<double> wander(0.0, cg_spread_m);
    std::vector<pe::HoverThrusts> out;
    for (int i = 0; i < count; ++i) out.push_back(hover({wander(random), wander(random)}, random));
    return out;
  }
};

// The same vehicle with rotor `weak` giving `factor` of its thrust and `torque` of its drag torque
// per thrust (a chipped blade loses both).
Quad damaged(Quad quad, int weak, double factor, double torque = 1.0) {
  quad.thrust_factor[weak] *= factor;
  quad.torque_per_thrust[weak] *= torque;
  return quad;
}

}  // namespace

TEST(MotorChange, SharesSumToOneAndTheIdealOfASymmetricQuadIsAQuarterEach) {
  const std::vector<double> shares = pe::thrustShares({1.0, 2.0, 3.0, 4.0});
  EXPECT_DOUBLE_EQ(shares[3], 0.4);
  EXPECT_TRUE(pe::thrustShares({0.0, 0.0, 0.0, 0.0}).empty());
  for (double share : pe::idealShares(pe::Vehicle::quadX(0.2))) EXPECT_NEAR(share, 0.25, 1e-12);
}

TEST(MotorChange, ARotorWeakAloneIsPutOnItsOwnMotorAgainstTheVehiclesReference) {
  // A propeller at 92 % of its thrust, on each motor of five vehicles whose parts differ: six
  // healthy flights teach the reference, three damaged flights are judged.
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Quad quad(seed);
    std::mt19937 random(100 + seed);
    const pe::MotorReference reference = pe::learnMotorReference(quad.vehicle, quad.flights(6, random));
    for (int weak = 0; weak < 4; ++weak) {
      for (double torque : {1.0, 0.9}) {
        const pe::MotorChangeVerdict verdict = pe::judgeAgainstReference(
            quad.vehicle, reference, damaged(quad, weak, 0.92, torque).flights(3, random), pe::MotorChangeRule());
        EXPECT_EQ(verdict.suspect, weak) << "seed " << seed << ", torque " << torque;
        EXPECT_NEAR(verdict.motors[weak].gap, 1.0 / 0.92 - 1.0, 0.04) << "seed " << seed;
      }
    }
  }
}

TEST(MotorChange, NoHealthyFlightAndNoChangeCommonToAllRotorsNamesAMotor) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Quad quad(seed);
    std::mt19937 random(200 + seed);
    const pe::MotorReference reference = pe::learnMotorReference(quad.vehicle, quad.flights(6, random));
    Quad worn = quad;
    for (double& factor : worn.thrust_factor) factor *= 0.94;
    for (const Quad& judged : {quad, worn}) {
      const pe::MotorChangeVerdict verdict =
          pe::judgeAgainstReference(quad.vehicle, reference, judged.flights(3, random), pe::MotorChangeRule());
      EXPECT_EQ(verdict.suspect, -1) << "seed " << seed;
    }
  }
}

TEST(MotorChange, TheDiagonalPartnerOfAWeakRotorReadsStrongerNotWeaker) {
  const Quad quad(7);
  std::mt19937 random(7);
  const pe::MotorReference reference = pe::learnMotorReference(quad.vehicle, quad.flights(6, random));
  // quadX: rotors 0 (front right) and 1 (rear left) are a diagonal pair.
  const pe::MotorChangeVerdict verdict =
      pe::judgeAgainstReference(quad.vehicle, reference, damaged(quad, 0, 0.85).flights(3, random), pe::MotorChangeRule());
  EXPECT_EQ(verdict.suspect, 0);
  EXPECT_LT(verdict.motors[1].gap, 0.0);
}

TEST(MotorChange, WithoutAReferenceAHealthyVehicleIsNeverASuspectButAGrossFaultIs) {
  pe::MotorChangeRule rule;
  rule.healthy_gap_std = 0.067;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Quad quad(seed);
    std::mt19937 random(300 + seed);
    EXPECT_EQ(pe::judgeAgainstIdeal(quad.vehicle, quad.flights(3, random), rule).suspect, -1) << "seed " << seed;
    EXPECT_EQ(pe::judgeAgainstIdeal(quad.vehicle, damaged(quad, 2, 0.7).flights(3, random), rule).suspect, 2)
        << "seed " << seed;
  }
}

TEST(MotorChange, TheMotorGapThresholdHalvedOrDoubledChangesTheVerdicts) {
  // Near the threshold: a rotor at 93 % (gap 7.5 %, above min_gap 5 %, below 10 %) is found at
  // the default rule and lost when min_gap doubles; healthy vehicles (1 mm of centre-of-gravity
  // wander from flight to flight) raise at most one alarm in 40 at the default rule and three or
  // more when min_gap is halved.
  const Quad quad(11);
  std::mt19937 random(11);
  const pe::MotorReference reference = pe::learnMotorReference(quad.vehicle, quad.flights(8, random));
  const std::vector<pe::HoverThrusts> weak = damaged(quad, 3, 0.93).flights(6, random);
  pe::MotorChangeRule rule;
  EXPECT_EQ(pe::judgeAgainstReference(quad.vehicle, reference, weak, rule).suspect, 3);
  rule.min_gap = 0.10;
  EXPECT_EQ(pe::judgeAgainstReference(quad.vehicle, reference, weak, rule).suspect, -1);


  // Healthy vehicles, judged against their own reference: the alarms at the default rule and with
  // either threshold halved.
  const auto alarms = [](const pe::MotorChangeRule& judged_by) {
    int count = 0;
    for (unsigned seed = 1; seed <= 40; ++seed) {
      const Quad healthy(1000 + seed);
      std::mt19937 flights(seed);
      const pe::MotorReference own = pe::learnMotorReference(healthy.vehicle, healthy.flights(6, flights));
      count += pe::judgeAgainstReference(healthy.vehicle, own, healthy.flights(3, flights), judged_by).suspect >= 0;
    }
    return count;
  };
  pe::MotorChangeRule half_gap;
  half_gap.min_gap = 0.025;
  EXPECT_LE(alarms(pe::MotorChangeRule()), 1);
  EXPECT_GE(alarms(half_gap), 3);
}

TEST(MotorChange, WithoutGeometryOrWithTooFewFlightsItSaysWhy) {
  const Quad quad(1);
  std::mt19937 random(1);
  const pe::MotorReference reference = pe::learnMotorReference(quad.vehicle, quad.flights(3, random));
  EXPECT_EQ(pe::judgeAgainstReference(pe::Vehicle::upwardRotors(4), reference, quad.flights(2, random),
                                      pe::MotorChangeRule())
                .unavailable,
            "no rotor geometry (give --urdf or --frame)");
  EXPECT_EQ(pe::judgeAgainstReference(pe::Vehicle::frame("hexa_x", 0.3), reference, quad.flights(2, random),
                                      pe::MotorChangeRule())
                .unavailable,
            "the reference has 4 motors, the vehicle 6");
  try {
    pe::learnMotorReference(quad.vehicle, quad.flights(2, random));
    FAIL() << "two flights taught a reference";
  } catch (const pe::ConfigError& e) {
    EXPECT_STREQ(e.what(), "a motor reference needs steady hover on at least 3 healthy flights, got 2");
  }
  pe::MotorReference bad = reference;
  bad.shares[0] += 0.1;
  try {
    bad.validate();
    FAIL() << "shares summing to 1.1 passed";
  } catch (const pe::FieldError& e) {
    EXPECT_EQ(e.field(), "motor_reference.shares");
  }
}
