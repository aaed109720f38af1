#include "propulsion_estimator/vehicle/vehicle.h"

#include <cmath>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/number_format.h"

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

namespace {

// A motor of ArduPilot's AP_MotorsMatrix: its arm's angle in degrees clockwise from the nose seen
// from above, and its spin (+1 counter-clockwise).
struct FrameMotor {
  double angle_deg;
  int spin;
};

const std::vector<FrameMotor>* frameMotors(const std::string& name) {
  static const std::vector<FrameMotor> quad_x = {{45, 1}, {-135, 1}, {-45, -1}, {135, -1}};
  static const std::vector<FrameMotor> hexa_x = {{90, -1}, {-90, 1}, {-30, -1}, {150, 1}, {30, 1}, {-150, -1}};
  static const std::vector<FrameMotor> octo_x = {{22.5, -1}, {-157.5, -1}, {67.5, 1},  {157.5, 1},
                                                 {-22.5, 1}, {-112.5, 1},  {-67.5, -1}, {112.5, -1}};
  if (name == "quad_x") return &quad_x;
  if (name == "hexa_x") return &hexa_x;
  if (name == "octo_x") return &octo_x;
  return nullptr;
}

}  // namespace

std::vector<std::string> Vehicle::frameNames() { return {"quad_x", "hexa_x", "octo_x"}; }

Vehicle Vehicle::frame(const std::string& name, double arm_length_m) {
  const std::vector<FrameMotor>* motors = frameMotors(name);
  if (!motors) throw ConfigError("--frame: unknown frame '" + name + "' (known: " + joined(frameNames()) + ")");
  if (!(arm_length_m >= kMinArmM && arm_length_m <= kMaxArmM)) {
    throw ConfigError("--arm-m: " + formatNumber(arm_length_m) + " is outside " + formatNumber(kMinArmM) + ".." +
                      formatNumber(kMaxArmM) + " m");
  }
  Vehicle vehicle;
  for (std::size_t k = 0; k < motors->size(); ++k) {
    const double angle = (*motors)[k].angle_deg * M_PI / 180.0;
    Rotor rotor;
    rotor.name = "rotor_" + std::to_string(k + 1);
    // Clockwise from the nose is towards -y in REP-103's body frame (y left).
    rotor.position_m = Eigen::Vector3d(arm_length_m * std::cos(angle), -arm_length_m * std::sin(angle), 0.0);
    rotor.spin_direction = (*motors)[k].spin;
    vehicle.rotors.push_back(rotor);
  }
  return vehicle;
}

}  // namespace propulsion_estimator
