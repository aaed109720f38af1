#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "propulsion_estimator/sim/flight/airframe.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace sim {

/// Rigid-body multicopter over flat ground, with a payload hanging on a cable that only pulls
/// (a spring-damper along the cable: a pendulum while taut, slack when the payload rests on the
/// ground). The vehicle stands on four feet of its landing gear; feet and payload meet the ground
/// through stiff spring-dampers with Coulomb friction. World frame ENU with the ground at z = 0,
/// body frame FLU at base_link. Semi-implicit Euler, for steps of about 2 ms; the cable's tension
/// by backward Euler along the cable, because the stretch mode of a light payload on a stiff,
/// damped cable (10 g on 1000 N/m and 10 N s/m: 316 rad/s, damping rate c/m = 1000 /s) is far
/// faster than the step, and an explicit step would diverge. The constructor throws ConfigError for
/// a vehicle without rotor positions or empty mass properties.
class MultirotorDynamics {
 public:
  /// `vehicle` needs its rotors' geometry and empty mass properties. The vehicle starts landed at
  /// the origin, level, facing east (x); no payload.
  MultirotorDynamics(const Vehicle& vehicle, const VehicleSetup& setup, const PayloadCable& cable);

  /// Advances by dt under the rotors' thrusts (N, along each rotor's axis) and the propellers'
  /// aerodynamic torques (N m, positive; the body feels -spin * torque about the axis), in air of
  /// `air_density_kg_m3` (drag).
  void step(const std::vector<double>& thrust_n, const std::vector<double>& torque_nm, double air_density_kg_m3,
            double dt_s);

  /// Puts a payload of `mass_kg` (0: none) on the ground under the attachment point, at rest.
  void setPayload(double mass_kg);

  Eigen::Vector3d basePosition() const;  ///< base_link in the world
  Eigen::Vector3d baseVelocity() const;  ///< base_link's velocity in the world, m/s
  /// Rotates body into world.
  const Eigen::Quaterniond& attitude() const { return attitude_; }
  /// rad/s, body frame.
  const Eigen::Vector3d& angularVelocityBody() const { return omega_body_; }
  /// Non-gravitational acceleration of the centre of mass in the body frame: what an accelerometer
  /// there reads (the IMU's lever arm of a few centimetres is neglected).
  const Eigen::Vector3d& specificForceBody() const { return specific_force_body_; }
  Eigen::Vector3d rotorPosition(int k) const;  ///< in the world
  Eigen::Vector3d rotorVelocity(int k) const;  ///< of rotor k's hub, in the world
  /// N, 0 while slack
  double cableTensionN() const { return cable_tension_n_; }
  /// Whether a foot or the payload pressed on the ground during the last step.
  bool touchedGround() const { return touched_ground_; }
  /// kg, 0 without payload.
  double payloadMassKg() const { return payload_mass_kg_; }
  /// kg, the vehicle without payload.
  double vehicleMassKg() const { return mass_kg_; }

  /// Whether the whole state (vehicle and payload) is finite.
  bool isFinite() const;

 private:
  /// Tension of the taut cable over the next step, given its direction from the attachment point
  /// to the payload, its stretch, and every other force on the payload and the vehicle.
  double cableTension(const Eigen::Vector3d& along, double stretch_m, const Eigen::Vector3d& payload_force,
                      const Eigen::Vector3d& vehicle_force, const Eigen::Vector3d& vehicle_torque_body,
                      double dt_s) const;
  Eigen::Vector3d worldPoint(const Eigen::Vector3d& body_point) const;
  Eigen::Vector3d worldPointVelocity(const Eigen::Vector3d& body_point) const;

  std::vector<Rotor> rotors_;
  double mass_kg_;
  Eigen::Matrix3d inertia_;
  Eigen::Matrix3d inertia_inverse_;
  Eigen::Vector3d centre_of_mass_body_;
  std::array<Eigen::Vector3d, 4> feet_body_;
  double foot_stiffness_n_per_m_;
  double foot_damping_n_s_per_m_;
  double drag_area_m2_;
  PayloadCable cable_;

  /// Centre of mass state.
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond attitude_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d omega_body_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d specific_force_body_ = Eigen::Vector3d::Zero();

  double payload_mass_kg_ = 0.0;
  Eigen::Vector3d payload_position_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d payload_velocity_ = Eigen::Vector3d::Zero();
  double cable_tension_n_ = 0.0;
  bool touched_ground_ = true;  ///< it starts landed
};

}  // namespace sim
}  // namespace propulsion_estimator
