#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "propulsion_estimator/sim/flight/airframe.h"
#include "propulsion_estimator/sim/flight/motor_mixer.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace sim {

/// The vehicle's state as the autopilot's estimator gives it (the simulator passes the true state).
struct NavigationState {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< base_link, world ENU
  Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();  ///< base_link, world ENU, m/s
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();  ///< rotates body (FLU) into world (ENU)
  Eigen::Vector3d angular_velocity_body_rad_s = Eigen::Vector3d::Zero();  ///< body frame
};

/// What the script asks of the controller at one instant: height of base_link in m, feed-forward
/// vertical speed in m/s, whether it is landing, and the horizontal position with its feed-forward
/// velocity.
struct FlightSetpoint {
  double height_m = 0.0;  ///< m, base_link above the ground
  double vertical_speed_m_s = 0.0;  ///< feed-forward
  bool landing = false;             ///< the land detector runs only while landing
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  ///< east, north, m (ENU)
  Eigen::Vector2d velocity_m_s = Eigen::Vector2d::Zero();  ///< east, north feed-forward, m/s
};

/// A cascaded PX4-style controller that, like a real one, knows the geometry but nothing of the
/// propulsion physics: height -> vertical speed -> collective throttle, whose hover value an
/// integrator learns (starting from PX4's MPC_THR_HOVER default of 0.5); horizontal position and
/// velocity -> tilt; attitude -> body rates -> roll, pitch, yaw commands with integrators that take up a
/// centre-of-gravity offset; a geometric mixer; throttle to PWM between the autopilot's end
/// points. Armed on the ground the motors idle until a climb is commanded, then the collective
/// ramps up (PX4's take-off ramp). A land detector (low, still, for a second) disarms. The
/// constructor throws ConfigError as MotorMixer's does.
class FlightController {
 public:
  /// `landed_height_m`: base_link above the ground when landed. Throws ConfigError as MotorMixer's
  /// constructor does.
  FlightController(const Vehicle& vehicle, const AutopilotParams& autopilot, double landed_height_m);

  void arm();  ///< arms: the motors idle until a climb is commanded
  /// Pulse widths for the next control period.
  const std::vector<double>& update(const FlightSetpoint& setpoint, const NavigationState& state, double dt_s);

  /// Whether armed (the land detector disarms).
  bool armed() const { return armed_; }

 private:
  AutopilotParams autopilot_;
  MotorMixer mixer_;
  double landed_height_m_;
  bool armed_ = false;
  double hover_throttle_;
  double takeoff_ramp_ = 0.0;  ///< upper limit of the collective while taking off
  Eigen::Vector3d rate_integral_ = Eigen::Vector3d::Zero();
  double landed_for_s_ = 0.0;
  std::vector<double> pwm_us_;
};

}  // namespace sim
}  // namespace propulsion_estimator
