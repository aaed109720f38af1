#pragma once

#include <Eigen/Core>
#include <vector>

#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace sim {

/// A flight controller's mixer, built from the rotor geometry alone (like PX4's geometry files):
/// the pseudo-inverse of the normalised allocation matrix [y/max|y|; -x/max|x|; -spin; 1/N], its
/// roll, pitch and yaw columns scaled so that the largest motor share of each is 1 (a quad X mixes
/// u = collective + roll y_sign - pitch x_sign - yaw spin). Like PX4's, it desaturates: a roll and
/// pitch demand that would push a motor above 1 lowers the collective instead, and yaw is scaled
/// down to the room left; outputs are then clamped to 0..1. The
/// constructor throws ConfigError for rotors without positions or a layout that cannot control
/// roll, pitch, yaw and thrust independently.
class MotorMixer {
 public:
  explicit MotorMixer(const Vehicle& vehicle);  ///< needs rotor positions

  /// Normalised motor outputs for a collective throttle (0..1) and roll, pitch, yaw commands
  /// (positive about body x, y, z).
  const std::vector<double>& mix(double collective, double roll, double pitch, double yaw);

 private:
  Eigen::Matrix<double, Eigen::Dynamic, 4> matrix_;  ///< motors x (roll, pitch, yaw, collective)
  Eigen::VectorXd commands_;                         ///< unclamped outputs, sized once: mix() does not allocate
  std::vector<double> outputs_;
};

}  // namespace sim
}  // namespace propulsion_estimator
