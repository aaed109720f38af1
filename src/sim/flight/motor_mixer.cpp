#include "propulsion_estimator/sim/flight/motor_mixer.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/config_error.h"

namespace propulsion_estimator {
namespace sim {

MotorMixer::MotorMixer(const Vehicle& vehicle) {
  if (!vehicle.hasGeometry()) throw ConfigError("the mixer needs the rotors' positions");
  const int n = static_cast<int>(vehicle.rotors.size());
  double max_x = 0.0, max_y = 0.0;
  for (const Rotor& rotor : vehicle.rotors) {
    max_x = std::max(max_x, std::fabs(rotor.position_m.x()));
    max_y = std::max(max_y, std::fabs(rotor.position_m.y()));
  }
  Eigen::MatrixXd allocation(4, n);
  for (int k = 0; k < n; ++k) {
    const Rotor& rotor = vehicle.rotors[k];
    allocation(0, k) = max_y > 0.0 ? rotor.position_m.y() / max_y : 0.0;
    allocation(1, k) = max_x > 0.0 ? -rotor.position_m.x() / max_x : 0.0;
    allocation(2, k) = -rotor.spin_direction;
    allocation(3, k) = 1.0 / n;
  }
  // Pseudo-inverse A^T (A A^T)^-1 of the full-row-rank allocation.
  const Eigen::Matrix4d gram = allocation * allocation.transpose();
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(gram);
  if (lu.rank() < 4) throw ConfigError("the rotor layout cannot control roll, pitch, yaw and thrust independently");
  matrix_ = allocation.transpose() * lu.inverse();
  for (int axis = 0; axis < 3; ++axis) {
    const double largest = matrix_.col(axis).cwiseAbs().maxCoeff();
    if (largest > 0.0) matrix_.col(axis) /= largest;
  }
  commands_.resize(n);
  outputs_.assign(n, 0.0);
}

const std::vector<double>& MotorMixer::mix(double collective, double roll, double pitch, double yaw) {
  // PX4's desaturation: roll and pitch come first, so a motor at full output lowers the collective
  // rather than losing the differential that holds the attitude; yaw gets what room is left. Clamping
  // alone would tilt a heavy vehicle climbing near full throttle.
  commands_.noalias() = matrix_ * Eigen::Vector4d(roll, pitch, 0.0, collective);
  const double top = commands_.maxCoeff();
  if (top > 1.0) commands_.array() -= std::min(top - 1.0, collective);
  double yaw_share = 1.0;
  for (int k = 0; k < commands_.size(); ++k) {
    const double base = commands_(k);
    const double turn = matrix_(k, 2) * yaw;
    if (base + turn > 1.0) yaw_share = std::min(yaw_share, std::max(0.0, (1.0 - base) / turn));
    if (base + turn < 0.0) yaw_share = std::min(yaw_share, std::max(0.0, -base / turn));
  }
  commands_ += yaw_share * yaw * matrix_.col(2);
  for (std::size_t k = 0; k < outputs_.size(); ++k) outputs_[k] = std::clamp(commands_(k), 0.0, 1.0);
  return outputs_;
}

}  // namespace sim
}  // namespace propulsion_estimator
