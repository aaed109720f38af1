// Common frames by name, in ArduPilot's motor order, for users without a URDF; the order and spin
// checked against each autopilot's own geometry (PX4's mixer geometries and ArduPilot's
// AP_MotorsMatrix), transcribed below as numbers, not code.
#include <cmath>
#include <string>
#include <vector>

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

namespace {

// One motor as an autopilot's geometry gives it: position in its body frame FRD (x forward, y
// right), unit arm, and spin seen from above (+1 counter-clockwise).
struct AutopilotMotor {
  double x_forward, y_right;
  int spin;
};

void expectFrame(const std::string& name, const std::vector<AutopilotMotor>& motors, const std::string& source) {
  const pe::Vehicle vehicle = pe::Vehicle::frame(name, 1.0);
  ASSERT_EQ(vehicle.rotors.size(), motors.size()) << name << " vs " << source;
  for (std::size_t k = 0; k < motors.size(); ++k) {
    // FRD to REP-103's FLU: y right is -y.
    EXPECT_NEAR(vehicle.rotors[k].position_m.x(), motors[k].x_forward, 1e-6) << name << " motor " << k + 1 << ", " << source;
    EXPECT_NEAR(vehicle.rotors[k].position_m.y(), -motors[k].y_right, 1e-6) << name << " motor " << k + 1 << ", " << source;
    EXPECT_EQ(vehicle.rotors[k].spin_direction, motors[k].spin) << name << " motor " << k + 1 << ", " << source;
  }
}

// ArduPilot's add_motor(angle, yaw factor): the arm at `angle_deg` clockwise from the nose.
AutopilotMotor ardupilot(double angle_deg, int spin) {
  const double a = angle_deg * M_PI / 180.0;
  return {std::cos(a), std::sin(a), spin};
}

constexpr int kCw = -1, kCcw = 1;

}  // namespace

// PX4: the quad X of its control-allocation airframes (CA_ROTOR0..3 PX, PY and the sign of KM,
// positive counter-clockwise, as in 4001_gz_x500), and its mixer geometries
// src/lib/mixer/MultirotorMixer/geometries/hex_x.toml and octa_x.toml (rotor positions FRD,
// direction): the order PX4's outputs 1..n drive.
TEST(VehicleFrames, MatchPx4sOwnGeometries) {
  const double h = std::sqrt(0.5), c = 0.866025, s = 0.5, a = 0.9238795, b = 0.3826834;
  expectFrame("quad_x", {{h, h, kCcw}, {-h, -h, kCcw}, {h, -h, kCw}, {-h, h, kCw}}, "PX4 quad X (CA_ROTOR)");
  expectFrame("hexa_x",
              {{0, 1, kCw}, {0, -1, kCcw}, {c, -s, kCw}, {-c, s, kCcw}, {c, s, kCcw}, {-c, -s, kCw}},
              "PX4 hex_x.toml");
  expectFrame("octo_x",
              {{a, b, kCw}, {-a, -b, kCw}, {b, a, kCcw}, {-a, b, kCcw}, {a, -b, kCcw}, {-b, -a, kCcw}, {b, -a, kCw},
               {-b, a, kCw}},
              "PX4 octa_x.toml");
}

// ArduPilot: libraries/AP_Motors/AP_MotorsMatrix.cpp, MOTOR_FRAME_TYPE_X of the quad, hexa and
// octa classes (angle and yaw factor of AP_MOTORS_MOT_1..n).
TEST(VehicleFrames, MatchArduPilotsOwnGeometries) {
  expectFrame("quad_x", {ardupilot(45, kCcw), ardupilot(-135, kCcw), ardupilot(-45, kCw), ardupilot(135, kCw)},
              "ArduPilot quad X");
  expectFrame("hexa_x",
              {ardupilot(90, kCw), ardupilot(-90, kCcw), ardupilot(-30, kCw), ardupilot(150, kCcw), ardupilot(30, kCcw),
               ardupilot(-150, kCw)},
              "ArduPilot hexa X");
  expectFrame("octo_x",
              {ardupilot(22.5, kCw), ardupilot(-157.5, kCw), ardupilot(67.5, kCcw), ardupilot(157.5, kCcw),
               ardupilot(-22.5, kCcw), ardupilot(-112.5, kCcw), ardupilot(-67.5, kCw), ardupilot(112.5, kCw)},
              "ArduPilot octa X");
}
