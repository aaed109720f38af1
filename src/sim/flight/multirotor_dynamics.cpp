#include "propulsion_estimator/sim/flight/multirotor_dynamics.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace sim {
namespace {

const Eigen::Vector3d kGravity(0.0, 0.0, -kStandardGravity);

// Ground contact: stiff enough that a foot sinks ~1 mm under the vehicle, damped to 0.8 of
// critical; Coulomb friction of rubber feet on a floor, viscous below 5 cm/s of sliding. The
// regularisation keeps the explicit step stable: the friction's rate mu g / v = 160 /s times the
// 2 ms step stays well below 1 (at 1 cm/s it would exceed 1 and the feet would chatter).
constexpr double kContactFrequencyHz = 15.0;
constexpr double kContactDampingRatio = 0.8;
constexpr double kFrictionCoefficient = 0.8;
constexpr double kFrictionRegularisationM_S = 0.05;
// Rotational damping of the airframe and its rotors (blade flapping), N m s/rad, assumed.
constexpr double kAngularDampingNmS = 0.002;
// Cd A of a small payload (a 10 cm box).
constexpr double kPayloadDragAreaM2 = 0.01;

// Stiffness and damping of a contact carrying `mass_kg`: it rings at kContactFrequencyHz.
double contactStiffness(double mass_kg) { return mass_kg * std::pow(kTwoPi * kContactFrequencyHz, 2); }
double contactDamping(double mass_kg) {
  return 2.0 * kContactDampingRatio * std::sqrt(contactStiffness(mass_kg) * mass_kg);
}

// Normal and friction force of the ground on a point at `position` moving at `velocity`, for a
// contact of stiffness k and damping c.
Eigen::Vector3d groundForce(const Eigen::Vector3d& position, const Eigen::Vector3d& velocity, double k, double c) {
  if (position.z() >= 0.0) return Eigen::Vector3d::Zero();
  const double normal = std::max(0.0, -k * position.z() - c * velocity.z());
  const Eigen::Vector2d sliding(velocity.x(), velocity.y());
  const Eigen::Vector2d friction =
      -sliding / std::max(sliding.norm(), kFrictionRegularisationM_S) * kFrictionCoefficient * normal;
  return Eigen::Vector3d(friction.x(), friction.y(), normal);
}

Eigen::Vector3d drag(const Eigen::Vector3d& velocity, double density, double area) {
  return -0.5 * density * area * velocity.norm() * velocity;
}

}  // namespace

MultirotorDynamics::MultirotorDynamics(const Vehicle& vehicle, const VehicleSetup& setup, const PayloadCable& cable)
    : rotors_(vehicle.rotors), drag_area_m2_(setup.drag_area_m2), cable_(cable) {
  if (!vehicle.hasGeometry() || !vehicle.empty_mass) {
    throw ConfigError(
        "the flight simulator needs the rotors' positions and the mass properties of the vehicle (a URDF "
        "with rotor joints and <inertial> elements)");
  }
  mass_kg_ = vehicle.empty_mass->mass_kg;
  // The URDF's inertia about its own centre of mass; the configured offset of a few millimetres
  // changes it by m d^2 < 1e-4 kg m^2, which is neglected.
  inertia_ = vehicle.empty_mass->inertia_kg_m2;
  inertia_inverse_ = inertia_.inverse();
  centre_of_mass_body_ = vehicle.empty_mass->centre_of_mass_m + setup.centre_of_mass_offset_m;
  const double w = setup.landing_gear_half_width_m;
  const double h = setup.landing_gear_height_m;
  feet_body_ = {Eigen::Vector3d(w, w, -h), Eigen::Vector3d(w, -w, -h), Eigen::Vector3d(-w, w, -h),
                Eigen::Vector3d(-w, -w, -h)};
  // Each foot carries its share of the vehicle; at rest it is sunk by that weight over its stiffness.
  const double foot_mass = mass_kg_ / feet_body_.size();
  foot_stiffness_n_per_m_ = contactStiffness(foot_mass);
  foot_damping_n_s_per_m_ = contactDamping(foot_mass);
  const double sink = mass_kg_ * kStandardGravity / (feet_body_.size() * foot_stiffness_n_per_m_);
  position_ = Eigen::Vector3d(0.0, 0.0, h - sink) + centre_of_mass_body_;
  specific_force_body_ = -kGravity;  // the ground holds the weight
}

Eigen::Vector3d MultirotorDynamics::worldPoint(const Eigen::Vector3d& body_point) const {
  return position_ + attitude_ * (body_point - centre_of_mass_body_);
}

Eigen::Vector3d MultirotorDynamics::worldPointVelocity(const Eigen::Vector3d& body_point) const {
  return velocity_ + attitude_ * omega_body_.cross(body_point - centre_of_mass_body_);
}

Eigen::Vector3d MultirotorDynamics::basePosition() const { return worldPoint(Eigen::Vector3d::Zero()); }
Eigen::Vector3d MultirotorDynamics::baseVelocity() const { return worldPointVelocity(Eigen::Vector3d::Zero()); }
Eigen::Vector3d MultirotorDynamics::rotorPosition(int k) const { return worldPoint(rotors_[k].position_m); }
Eigen::Vector3d MultirotorDynamics::rotorVelocity(int k) const { return worldPointVelocity(rotors_[k].position_m); }

void MultirotorDynamics::setPayload(double mass_kg) {
  payload_mass_kg_ = mass_kg;
  const Eigen::Vector3d attach = worldPoint(cable_.attach_point_m);
  payload_position_ = Eigen::Vector3d(attach.x(), attach.y(), 0.0);
  payload_velocity_.setZero();
  cable_tension_n_ = 0.0;
}

bool MultirotorDynamics::isFinite() const {
  return position_.allFinite() && velocity_.allFinite() && attitude_.coeffs().allFinite() && omega_body_.allFinite() &&
         payload_position_.allFinite() && payload_velocity_.allFinite();
}

double MultirotorDynamics::cableTension(const Eigen::Vector3d& along, double stretch_m,
                                        const Eigen::Vector3d& payload_force, const Eigen::Vector3d& vehicle_force,
                                        const Eigen::Vector3d& vehicle_torque_body, double dt_s) const {
  // The attachment point moves along the cable with the vehicle's translation and rotation: it
  // answers a pull T along the cable with the acceleration T (1/M + w' I^-1 w), w = r x u in the
  // body frame, and the other forces and torques give it the acceleration a_v.u + alpha.w.
  const Eigen::Vector3d lever = cable_.attach_point_m - centre_of_mass_body_;
  const Eigen::Vector3d w = lever.cross(attitude_.conjugate() * along);
  const double attach_mobility = 1.0 / mass_kg_ + w.dot(inertia_inverse_ * w);
  const Eigen::Vector3d angular_acceleration =
      inertia_inverse_ * (vehicle_torque_body - omega_body_.cross(inertia_ * omega_body_));
  const double reduced_mass = 1.0 / (1.0 / payload_mass_kg_ + attach_mobility);
  // Gravity accelerates both ends alike.
  const double relative_acceleration =
      (payload_force / payload_mass_kg_ - vehicle_force / mass_kg_).dot(along) - angular_acceleration.dot(w);
  const double stretch_rate = (payload_velocity_ - worldPointVelocity(cable_.attach_point_m)).dot(along);
  // Backward Euler on the stretch s: T = k (s + dt s') + c s' with s' the rate at the end of the
  // step, s' = rate + dt (relative_acceleration - T / reduced_mass).
  const double k = cable_.stiffness_n_per_m;
  const double c = cable_.damping_n_s_per_m;
  const double next_rate = (stretch_rate + dt_s * (relative_acceleration - k * stretch_m / reduced_mass)) /
                           (1.0 + dt_s * (k * dt_s + c) / reduced_mass);
  return std::max(0.0, k * (stretch_m + dt_s * next_rate) + c * next_rate);
}

void MultirotorDynamics::step(const std::vector<double>& thrust_n, const std::vector<double>& torque_nm,
                              double air_density_kg_m3, double dt_s) {
  Eigen::Vector3d force = drag(velocity_, air_density_kg_m3, drag_area_m2_);
  Eigen::Vector3d torque_body = -kAngularDampingNmS * omega_body_;
  const auto applyBody = [&](const Eigen::Vector3d& point_body, const Eigen::Vector3d& force_body) {
    force += attitude_ * force_body;
    torque_body += (point_body - centre_of_mass_body_).cross(force_body);
  };
  for (std::size_t k = 0; k < rotors_.size(); ++k) {
    applyBody(rotors_[k].position_m, thrust_n[k] * rotors_[k].thrust_axis);
    torque_body -= rotors_[k].spin_direction * torque_nm[k] * rotors_[k].thrust_axis;
  }

  touched_ground_ = false;
  for (const Eigen::Vector3d& foot : feet_body_) {
    const Eigen::Vector3d contact =
        groundForce(worldPoint(foot), worldPointVelocity(foot), foot_stiffness_n_per_m_, foot_damping_n_s_per_m_);
    touched_ground_ = touched_ground_ || contact.z() > 0.0;
    applyBody(foot, attitude_.conjugate() * contact);
  }

  cable_tension_n_ = 0.0;
  if (payload_mass_kg_ > 0.0) {
    const Eigen::Vector3d payload_contact = groundForce(
        payload_position_, payload_velocity_, contactStiffness(payload_mass_kg_), contactDamping(payload_mass_kg_));
    touched_ground_ = touched_ground_ || payload_contact.z() > 0.0;
    Eigen::Vector3d payload_force = payload_contact + drag(payload_velocity_, air_density_kg_m3, kPayloadDragAreaM2);
    const Eigen::Vector3d span = payload_position_ - worldPoint(cable_.attach_point_m);
    const double length = span.norm();
    if (length > cable_.length_m) {
      const Eigen::Vector3d along = span / length;
      cable_tension_n_ = cableTension(along, length - cable_.length_m, payload_force, force, torque_body, dt_s);
      const Eigen::Vector3d pull = cable_tension_n_ * along;
      applyBody(cable_.attach_point_m, attitude_.conjugate() * pull);
      payload_force -= pull;
    }
    payload_velocity_ += (payload_force / payload_mass_kg_ + kGravity) * dt_s;
    payload_position_ += payload_velocity_ * dt_s;
  }

  const Eigen::Vector3d acceleration = force / mass_kg_;
  specific_force_body_ = attitude_.conjugate() * acceleration;
  velocity_ += (acceleration + kGravity) * dt_s;
  position_ += velocity_ * dt_s;

  const Eigen::Vector3d angular_acceleration =
      inertia_inverse_ * (torque_body - omega_body_.cross(inertia_ * omega_body_));
  omega_body_ += angular_acceleration * dt_s;
  const double angle = omega_body_.norm() * dt_s;
  if (angle > 0.0) {
    attitude_ = (attitude_ * Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega_body_.normalized()))).normalized();
  }
}

}  // namespace sim
}  // namespace propulsion_estimator
