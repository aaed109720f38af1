#pragma once

#include <vector>

#include <Eigen/Core>

#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {

/// The moment balance of a multicopter in steady hover, from each rotor's thrust in N (in rotor
/// order). The rotors' drag torques cancel (yaw) and the thrusts balance about the centre of
/// gravity (roll, pitch). A centre of gravity away from the URDF's moves only the roll and pitch
/// balance, all shares together, so thrusts a model gives right still cancel in yaw:
/// sum(s_k T_k) = 0, s_k the spin direction (drag torque proportional to thrust for identical
/// propellers). A motor whose model reads high by a fraction e_j (a damaged propeller, a worn
/// motor: less thrust than modelled at its PWM) breaks the yaw balance by s_j T_j e_j.
/// The rotor positions must be known (Vehicle::hasGeometry) for thrustCentre and impliedCentre.

/// sum(s_k T_k) / sum(T_k): the yaw imbalance as a share of the total thrust.
double yawImbalance(const Vehicle& vehicle, const std::vector<double>& thrust_n);

/// Where the thrusts' resultant pierces the rotor plane, x and y in m in the body frame.
Eigen::Vector2d thrustCentre(const Vehicle& vehicle, const std::vector<double>& thrust_n);

/// The fraction of its modelled thrust motor `j` (0-based) would lack for the yaw imbalance
/// `yaw` (yawImbalance) to vanish, if it alone were off: yaw x sum(T) / (s_j T_j).
double weakMotorGap(const Vehicle& vehicle, const std::vector<double>& thrust_n, double yaw, int j);

/// The thrust centre in m if motor `j` gave (1 - gap) of its modelled thrust.
Eigen::Vector2d impliedCentre(const Vehicle& vehicle, const std::vector<double>& thrust_n, int j, double gap);

}  // namespace propulsion_estimator
