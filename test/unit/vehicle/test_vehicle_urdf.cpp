#include <gtest/gtest.h>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

TEST(VehicleUrdf, ReadsTheShippedF450) {
  const pe::Vehicle vehicle = pe::loadVehicleUrdf(repoPath("config/f450_quad.urdf"));
  ASSERT_EQ(vehicle.rotors.size(), 4u);
  ASSERT_TRUE(vehicle.empty_mass.has_value());
  EXPECT_NEAR(vehicle.empty_mass->mass_kg, 1.315, 1e-9);
  // Motor 1 is front-right and turns counter-clockwise, motor 3 front-left clockwise.
  EXPECT_NEAR(vehicle.rotors[0].position_m.x(), 0.1591, 1e-9);
  EXPECT_NEAR(vehicle.rotors[0].position_m.y(), -0.1591, 1e-9);
  EXPECT_EQ(vehicle.rotors[0].spin_direction, 1);
  EXPECT_EQ(vehicle.rotors[2].spin_direction, -1);
  EXPECT_TRUE(vehicle.rotors[3].thrust_axis.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(vehicle.hasGeometry());
  // The battery hangs below the base link: the centre of mass is below it too.
  EXPECT_LT(vehicle.empty_mass->centre_of_mass_m.z(), 0.0);
  EXPECT_GT(vehicle.empty_mass->inertia_kg_m2(2, 2), vehicle.empty_mass->inertia_kg_m2(0, 0));
}

TEST(VehicleUrdf, TiltedRotorJointTiltsTheThrustAxis) {
  const std::string xml = R"(<robot name="r"><link name="base_link"/><link name="p"/>
    <joint name="rotor_1_joint" type="continuous"><parent link="base_link"/><child link="p"/>
    <origin xyz="0.2 0 0" rpy="0.1 0 0"/><axis xyz="0 0 -1"/></joint></robot>)";
  const pe::Vehicle vehicle = pe::vehicleFromUrdf(xml, "tilted.urdf");
  ASSERT_EQ(vehicle.rotors.size(), 1u);
  EXPECT_NEAR(vehicle.rotors[0].thrust_axis.z(), std::cos(0.1), 1e-12);
  EXPECT_NEAR(vehicle.rotors[0].thrust_axis.y(), -std::sin(0.1), 1e-12);
  EXPECT_EQ(vehicle.rotors[0].spin_direction, -1);
  EXPECT_FALSE(vehicle.empty_mass.has_value());
}

TEST(VehicleUrdf, RefusesBadDescriptions) {
  auto refusal = [](const std::string& xml) -> std::string {
    try {
      pe::vehicleFromUrdf(xml, "v.urdf");
    } catch (const pe::ConfigError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_EQ(refusal("not xml"), "v.urdf: not a valid URDF robot description");
  EXPECT_EQ(refusal(R"(<robot name="r"><link name="base_link"/></robot>)"),
            "v.urdf: no rotor joints (expected joints named rotor_1_joint, rotor_2_joint, ...)");
  EXPECT_EQ(refusal(R"(<robot name="r"><link name="base_link"/><link name="p"/>
    <joint name="rotor_2_joint" type="continuous"><parent link="base_link"/><child link="p"/></joint></robot>)"),
            "v.urdf: rotor_1_joint is missing (rotors are numbered 1..1 without gaps)");
  EXPECT_EQ(refusal(R"(<robot name="r"><link name="base_link"/><link name="p"/>
    <joint name="rotor_1_joint" type="fixed"><parent link="base_link"/><child link="p"/></joint></robot>)"),
            "v.urdf: joint rotor_1_joint: a rotor joint must be continuous (or revolute)");
  // Not a motor number: an ordinary joint, so the description has no rotors.
  EXPECT_EQ(refusal(R"(<robot name="r"><link name="base_link"/><link name="p"/>
    <joint name="rotor_99999999999_joint" type="continuous"><parent link="base_link"/><child link="p"/></joint></robot>)"),
            "v.urdf: no rotor joints (expected joints named rotor_1_joint, rotor_2_joint, ...)");
  // Found by fuzz_vehicle_urdf (test/fuzz/regressions/vehicle_urdf/): urdfdom accepts a link that is
  // its own parent beside the root's tree, and the walk to the root never ended...
  EXPECT_EQ(refusal(R"(<robot name="r"><link name="base_link"/><link name="p"/>
    <joint name="rotor_1_joint" type="continuous"><parent link="p"/><child link="p"/></joint></robot>)"),
            "v.urdf: joint rotor_1_joint: closes a loop of links (a link would be its own ancestor)");
  // ... and leaks a loop's links, even in a description it refuses (here for its two roots).
  EXPECT_EQ(refusal(R"(<robot name="r"><link name="base_link"/><link name="a"/><link name="b"/><link name="c"/>
    <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
    <joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint></robot>)"),
            "v.urdf: joint j2: closes a loop of links (a link would be its own ancestor)");
  // Found by fuzz_vehicle_urdf: TinyXML read past the end of a text cut inside a UTF-8 character
  // (AddressSanitizer sees it in make test-sanitizers; here, the refusal).
  EXPECT_EQ(refusal(pe::readTextFile(repoPath("test/fuzz/regressions/vehicle_urdf/cut_inside_utf8_character.urdf"))),
            "v.urdf: not a valid URDF robot description");
}
