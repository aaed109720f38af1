#include "propulsion_estimator/vehicle/vehicle.h"

#include <cmath>

namespace propulsion_estimator {

bool Vehicle::hasGeometry() const {
  for (const Rotor& rotor : rotors) {
    if (!rotor.position_m.allFinite()) return false;
  }
  return !rotors.empty();
}

Vehicle Vehicle::upwardRotors(int n) {
  Vehicle vehicle;
  for (int k = 1; k <= n; ++k) vehicle.rotors.push_back(Rotor{"rotor_" + std::to_string(k)});
  return vehicle;
}

Vehicle Vehicle::quadX(double arm_length_m) {
  const double d = arm_length_m / std::sqrt(2.0);
  // Motor k: position (x, y) and spin; motors 1 and 2 turn counter-clockwise.
  const double layout[4][3] = {{d, -d, 1}, {-d, d, 1}, {d, d, -1}, {-d, -d, -1}};
  Vehicle vehicle;
  for (int k = 0; k < 4; ++k) {
    Rotor rotor;
    rotor.name = "rotor_" + std::to_string(k + 1);
    rotor.position_m = Eigen::Vector3d(layout[k][0], layout[k][1], 0.0);
    rotor.spin_direction = static_cast<int>(layout[k][2]);
    vehicle.rotors.push_back(rotor);
  }
  return vehicle;
}

}  // namespace propulsion_estimator
