// The autopilots' frames (body FRD, local NED) against the package's (body FLU, local ENU): a
// heading and a bank come out as REP-103 says, the swap undoes itself, and the specific force
// paired with an attitude is the latest within 0.1 s.
#include <gtest/gtest.h>

#include <cmath>

#include "propulsion_estimator/logs/autopilot_frames.h"

namespace pe = propulsion_estimator;

namespace {

Eigen::Quaterniond zyx(double roll, double pitch, double yaw) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
}

}  // namespace

TEST(AutopilotFrames, HeadingNorthInNedIsYawNinetyDegreesInEnu) {
  // Nose north, level: NED yaw 0; in ENU the nose (body x) points along +y.
  const Eigen::Quaterniond enu = pe::swapNedEnuFrdFlu(zyx(0.0, 0.0, 0.0));
  const Eigen::Vector3d nose = enu * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(nose.y(), 1.0, 1e-12);
  EXPECT_NEAR((enu * Eigen::Vector3d::UnitZ()).z(), 1.0, 1e-12);  // body up is world up
  // Nose east (NED yaw +90 degrees) is ENU yaw 0.
  EXPECT_NEAR((pe::swapNedEnuFrdFlu(zyx(0.0, 0.0, M_PI / 2)) * Eigen::Vector3d::UnitX()).x(), 1.0, 1e-12);
}

TEST(AutopilotFrames, RightWingDownInFrdIsTheLeftWingUpInFlu) {
  // Roll +30 degrees in FRD (right wing down): FLU's left wing (+y) points up.
  const Eigen::Quaterniond enu = pe::swapNedEnuFrdFlu(zyx(M_PI / 6, 0.0, 0.0));
  EXPECT_NEAR((enu * Eigen::Vector3d::UnitY()).z(), std::sin(M_PI / 6), 1e-12);
}

TEST(AutopilotFrames, TheSwapIsItsOwnInverse) {
  const Eigen::Quaterniond q = zyx(0.3, -0.2, 2.1);
  EXPECT_TRUE(pe::swapNedEnuFrdFlu(pe::swapNedEnuFrdFlu(q)).isApprox(q, 1e-12) ||
              pe::swapNedEnuFrdFlu(pe::swapNedEnuFrdFlu(q)).coeffs().isApprox(-q.coeffs(), 1e-12));
}

TEST(AutopilotFrames, PairsAnAttitudeWithTheLatestForceWithinATenthOfASecond) {
  pe::LatestSpecificForce latest({{1.0, Eigen::Vector3d(0, 0, 9.0)}, {2.0, Eigen::Vector3d(0, 0, 9.5)}});
  EXPECT_EQ(latest.at(0.9), nullptr);  // none yet
  ASSERT_NE(latest.at(1.05), nullptr);
  EXPECT_EQ(latest.at(1.05)->z(), 9.0);
  EXPECT_EQ(latest.at(1.2), nullptr);  // 0.2 s old
  ASSERT_NE(latest.at(2.0), nullptr);
  EXPECT_EQ(latest.at(2.0)->z(), 9.5);
  EXPECT_EQ(latest.at(3.0), nullptr);
}
