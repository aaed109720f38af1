#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace propulsion_estimator {

/// An autopilot's attitude (body FRD to local NED, PX4 and ArduPilot) as the package's (body FLU
/// to local ENU, REP-103), or back: the conversion is its own inverse. Throws nothing.
Eigen::Quaterniond swapNedEnuFrdFlu(const Eigen::Quaterniond& attitude);

/// The accelerometer's specific forces of one log (s on the manifest's clock, m/s^2 body FLU), in
/// time order, handed out as the latest one within 0.1 s before each attitude.
class LatestSpecificForce {
 public:
  /// `forces`: (time in s, specific force in m/s^2), in non-decreasing time.
  explicit LatestSpecificForce(std::vector<std::pair<double, Eigen::Vector3d>> forces) : forces_(std::move(forces)) {}

  /// The latest force at or before `time_s`, or nullptr when none is at most 0.1 s older; calls
  /// come in non-decreasing time. Throws nothing.
  const Eigen::Vector3d* at(double time_s);

 private:
  std::vector<std::pair<double, Eigen::Vector3d>> forces_;
  std::size_t next_ = 0;
};

}  // namespace propulsion_estimator
