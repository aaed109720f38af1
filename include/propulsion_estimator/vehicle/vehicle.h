#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "propulsion_estimator/common/not_a_number.h"

namespace propulsion_estimator {

/// One rotor in the body frame (REP-103: x forward, y left, z up), origin at the base link.
struct Rotor {
  std::string name;  ///< the URDF link's name
  Eigen::Vector3d position_m = Eigen::Vector3d::Constant(kNaN);  ///< m, base_link frame; NaN when unknown
  Eigen::Vector3d thrust_axis = Eigen::Vector3d::UnitZ();  ///< unit vector
  int spin_direction = 1;                                  ///< +1 counter-clockwise seen from above
};

/// Mass properties of a rigid body: mass in kg, centre of mass in m in the body frame, inertia
/// in kg m^2 about the centre of mass.
struct MassProperties {
  double mass_kg = 0.0;  ///< kg
  Eigen::Vector3d centre_of_mass_m = Eigen::Vector3d::Zero();  ///< m, base_link frame
  Eigen::Matrix3d inertia_kg_m2 = Eigen::Matrix3d::Zero();  ///< about the centre of mass
};

/// The multicopter: its rotors (in motor-channel order) and, when known, its empty mass
/// properties. Rotor positions are NaN when the geometry is unknown (no URDF given).
struct Vehicle {
  std::vector<Rotor> rotors;  ///< in RCOut channel order
  std::optional<MassProperties> empty_mass;  ///< from the URDF's inertials; none without one

  bool hasGeometry() const;  ///< whether every rotor's position is known

  /// n rotors thrusting along +z at unknown positions: what the thesis' method needs.
  static Vehicle upwardRotors(int n);
  /// Quad X in PX4/ArduPilot motor order (front-right, rear-left, front-left, rear-right).
  static Vehicle quadX(double arm_length_m);
  /// A common frame by name, rotors `arm_length_m` from the centre in the plane of the base link,
  /// in ArduPilot's motor order (AP_MotorsMatrix): "quad_x" (as quadX), "hexa_x", "octo_x".
  /// Throws ConfigError for another name or an arm length outside kMinArmM..kMaxArmM.
  static Vehicle frame(const std::string& name, double arm_length_m);
  /// m; the arm lengths frame() takes, from a micro quad's to a large octocopter's.
  ///@{
  static constexpr double kMinArmM = 0.03;
  static constexpr double kMaxArmM = 2.0;
  ///@}
  /// The names frame() knows.
  static std::vector<std::string> frameNames();
};

}  // namespace propulsion_estimator
