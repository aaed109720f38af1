// Common frames by name, in ArduPilot's motor order, for users without a URDF.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace pe = propulsion_estimator;

TEST(VehicleFrames, QuadXIsTheQuadXOfTheEstimator) {
  const pe::Vehicle named = pe::Vehicle::frame("quad_x", 0.225);
  const pe::Vehicle quad = pe::Vehicle::quadX(0.225);
  ASSERT_EQ(named.rotors.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_TRUE(named.rotors[k].position_m.isApprox(quad.rotors[k].position_m, 1e-12)) << k;
    EXPECT_EQ(named.rotors[k].spin_direction, quad.rotors[k].spin_direction) << k;
  }
  EXPECT_TRUE(named.hasGeometry());
}

TEST(VehicleFrames, HexaAndOctoBalanceTheirYawAndSitOnTheirArms) {
  for (const std::string name : {"hexa_x", "octo_x"}) {
    const pe::Vehicle vehicle = pe::Vehicle::frame(name, 0.4);
    ASSERT_EQ(vehicle.rotors.size(), name == "hexa_x" ? 6u : 8u);
    int spin = 0;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const pe::Rotor& rotor : vehicle.rotors) {
      EXPECT_NEAR(rotor.position_m.norm(), 0.4, 1e-12);
      spin += rotor.spin_direction;
      centre += rotor.position_m;
    }
    EXPECT_EQ(spin, 0) << name;
    EXPECT_LT(centre.norm(), 1e-12) << name;
  }
  // ArduPilot's hexa X: motor 1 on the right arm turning clockwise, motor 5 front-right counter-clockwise.
  const pe::Vehicle hexa = pe::Vehicle::frame("hexa_x", 0.4);
  EXPECT_NEAR(hexa.rotors[0].position_m.y(), -0.4, 1e-12);
  EXPECT_EQ(hexa.rotors[0].spin_direction, -1);
  EXPECT_GT(hexa.rotors[4].position_m.x(), 0.0);
  EXPECT_LT(hexa.rotors[4].position_m.y(), 0.0);
  EXPECT_EQ(hexa.rotors[4].spin_direction, 1);
}

TEST(VehicleFrames, RefusesAnUnknownFrameOrArm) {
  try {
    pe::Vehicle::frame("tri", 0.2);
    ADD_FAILURE() << "accepted";
  } catch (const pe::ConfigError& e) {
    EXPECT_STREQ(e.what(), "--frame: unknown frame 'tri' (known: quad_x, hexa_x, octo_x)");
  }
  try {
    pe::Vehicle::frame("quad_x", 0.0);
    ADD_FAILURE() << "accepted";
  } catch (const pe::ConfigError& e) {
    EXPECT_STREQ(e.what(), "--arm-m: 0 is outside 0.03..2 m");
  }
}
