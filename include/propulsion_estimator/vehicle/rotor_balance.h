#pragma once

#include <vector>

#include <Eigen/Core>

#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {

/// The moment balance of a multicopter in steady hover, from each rotor's thrust in N (in rotor
/// order). The rotors' drag torques cancel (yaw) and the thrusts balance about the centre of
/// gravity (roll, pitch). A centre of gravity away from the URDF's moves only the roll and pitch
/// balance, all shares together, so the thrusts of identical propellers cancel in yaw:
/// sum(s_k T_k) = 0, s_k the spin direction. Real propellers of the two spin directions are not
/// mirror images: estimation/motor_change.h judges the motors with that in mind.
/// The rotor positions must be known (Vehicle::hasGeometry) for thrustCentre.

/// sum(s_k T_k) / sum(T_k): the yaw imbalance as a share of the total thrust.
double yawImbalance(const Vehicle& vehicle, const std::vector<double>& thrust_n);

/// Where the thrusts' resultant pierces the rotor plane, x and y in m in the body frame.
Eigen::Vector2d thrustCentre(const Vehicle& vehicle, const std::vector<double>& thrust_n);

}  // namespace propulsion_estimator
