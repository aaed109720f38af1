#include "propulsion_estimator/sim/flight/flight_controller.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace sim {
namespace {

// Gains for a 1-2 kg quad on 9-10 in propellers, in throttle units (PX4's MPC_* and MC_* play
// the same roles). Height: 1.5 m/s per m; vertical speed: 0.1 throttle per m/s with an integral
// of 0.15 per m; horizontal: 1 m/s^2 per m and 1.5 m/s^2 per m/s, tilt within 20 deg.
constexpr double kHeightGain = 1.5;
constexpr double kMaxVerticalSpeedM_S = 2.0;
constexpr double kVerticalSpeedGain = 0.1;
constexpr double kHoverThrottleGain = 0.15;
constexpr double kInitialHoverThrottle = 0.5;
constexpr double kPositionGain = 1.0;
constexpr double kVelocityGain = 1.5;
constexpr double kMaxTiltRad = 0.35;
// PX4's MPC_TKO_RAMP_T: after arming the motors idle; once the climb is commanded the collective
// may rise from idle to full over this time.
constexpr double kTakeoffRampS = 2.0;
// Attitude error -> body rate (1/s), body rate error -> mixer command (per rad/s) and its integral.
// The roll and pitch integrals' zero, I/P = 1.3 rad/s as in PX4's defaults (MC_ROLLRATE_I 0.2 over
// P 0.15), lies well below the rate loop's crossover (about 10 rad/s on the thesis quad, lower on
// rotors that spin up more slowly or give less thrust per command). At 5 rad/s it took most of the
// phase margin: drawn hardware with 25 % more winding resistance (a slower spin-up) made the cascade
// ring at 1-2 Hz, growing until the vehicle flipped, mostly low and near landing, where the ground
// effect and the payload add loop gain.
const Eigen::Vector3d kAttitudeGain(4.0, 4.0, 2.5);
const Eigen::Vector3d kRateGain(0.03, 0.03, 0.25);
const Eigen::Vector3d kRateIntegralGain(0.04, 0.04, 0.2);
constexpr double kRateIntegralLimit = 0.3;
// Land detector: within 5 cm of the landed height and slower than 0.2 m/s for a second.
constexpr double kLandedMarginM = 0.05;
constexpr double kLandedSpeedM_S = 0.2;
constexpr double kLandedTimeS = 1.0;

}  // namespace

FlightController::FlightController(const Vehicle& vehicle, const AutopilotParams& autopilot, double landed_height_m)
    : autopilot_(autopilot),
      mixer_(vehicle),
      landed_height_m_(landed_height_m),
      hover_throttle_(kInitialHoverThrottle),
      pwm_us_(vehicle.rotors.size(), autopilot.disarmed_pwm_us) {}

void FlightController::arm() {
  armed_ = true;
  takeoff_ramp_ = 0.0;
  landed_for_s_ = 0.0;
  rate_integral_.setZero();
}

const std::vector<double>& FlightController::update(const FlightSetpoint& setpoint, const NavigationState& state,
                                                    double dt_s) {
  if (!armed_) {
    std::fill(pwm_us_.begin(), pwm_us_.end(), autopilot_.disarmed_pwm_us);
    return pwm_us_;
  }
  const double height = state.position_m.z();
  const bool near_ground = height < landed_height_m_ + kLandedMarginM;
  landed_for_s_ =
      setpoint.landing && near_ground && state.velocity_m_s.norm() < kLandedSpeedM_S ? landed_for_s_ + dt_s : 0.0;
  if (landed_for_s_ >= kLandedTimeS) {
    armed_ = false;
    std::fill(pwm_us_.begin(), pwm_us_.end(), autopilot_.disarmed_pwm_us);
    return pwm_us_;
  }

  // Vertical: height -> speed -> throttle; the integrator is the learned hover throttle, held
  // while the gear is expected on the ground, taking off or landing (where the height error says
  // nothing about the thrust).
  const bool takeoff_commanded =
      setpoint.vertical_speed_m_s > 0.0 || setpoint.height_m > landed_height_m_ + kLandedMarginM;
  if (takeoff_commanded || !near_ground) takeoff_ramp_ = std::min(1.0, takeoff_ramp_ + dt_s / kTakeoffRampS);
  const bool on_ground = near_ground && (setpoint.landing || takeoff_ramp_ < 1.0);
  const double speed_setpoint = std::clamp(setpoint.vertical_speed_m_s + kHeightGain * (setpoint.height_m - height),
                                           -kMaxVerticalSpeedM_S, kMaxVerticalSpeedM_S);
  const double speed_error = speed_setpoint - state.velocity_m_s.z();
  if (!on_ground) hover_throttle_ = std::clamp(hover_throttle_ + kHoverThrottleGain * speed_error * dt_s, 0.1, 0.9);
  const Eigen::Matrix3d rotation = state.attitude.toRotationMatrix();
  const double tilt_cosine = std::max(rotation(2, 2), 0.5);
  const double collective =
      std::clamp((hover_throttle_ + kVerticalSpeedGain * speed_error) / tilt_cosine, 0.0, takeoff_ramp_);

  // Horizontal: follow the setpoint, tilting towards the wanted acceleration (heading 0).
  const Eigen::Vector2d acceleration = kPositionGain * (setpoint.position_m - state.position_m.head<2>()) +
                                       kVelocityGain * (setpoint.velocity_m_s - state.velocity_m_s.head<2>());
  const double pitch = std::clamp(acceleration.x() / kStandardGravity, -kMaxTiltRad, kMaxTiltRad);
  const double roll = std::clamp(-acceleration.y() / kStandardGravity, -kMaxTiltRad, kMaxTiltRad);
  const Eigen::Quaterniond wanted = Eigen::Quaterniond(Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY())) *
                                    Eigen::Quaterniond(Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
  Eigen::Quaterniond error = state.attitude.conjugate() * wanted;
  if (error.w() < 0.0) error.coeffs() *= -1.0;
  const Eigen::Vector3d rate_setpoint = kAttitudeGain.cwiseProduct(2.0 * error.vec());
  const Eigen::Vector3d rate_error = rate_setpoint - state.angular_velocity_body_rad_s;
  if (!on_ground) {
    rate_integral_ = (rate_integral_ + kRateIntegralGain.cwiseProduct(rate_error) * dt_s)
                         .cwiseMax(-kRateIntegralLimit)
                         .cwiseMin(kRateIntegralLimit);
  }
  const Eigen::Vector3d command = kRateGain.cwiseProduct(rate_error) + rate_integral_;

  const std::vector<double>& outputs = mixer_.mix(collective, command.x(), command.y(), command.z());
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    // Autopilots output whole microseconds.
    pwm_us_[k] = std::round(autopilot_.pwm_min_us + outputs[k] * (autopilot_.pwm_max_us - autopilot_.pwm_min_us));
  }
  return pwm_us_;
}

}  // namespace sim
}  // namespace propulsion_estimator
