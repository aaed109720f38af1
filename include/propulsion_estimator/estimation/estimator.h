#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "propulsion_estimator/estimation/estimator_config.h"
#include "propulsion_estimator/estimation/hover_detector.h"
#include "propulsion_estimator/estimation/payload_estimator.h"
#include "propulsion_estimator/model/propulsion_model.h"
#include "propulsion_estimator/vehicle/vehicle.h"
#include "propulsion_estimator/estimation/vertical_acceleration_filter.h"

namespace propulsion_estimator {

// Why an input was not used. Every refused message is counted and leaves the estimates as they
// were: nothing is computed from it.
enum class Rejection {
  kNone = 0,
  kBadVoltage,      // battery voltage NaN, infinite, zero or negative
  kBadImu,          // non-finite or non-unit orientation, non-finite acceleration
  kBadVelocity,     // non-finite vertical speed
  kNoBattery,       // motor outputs before any valid voltage
  kStaleBattery,    // newest valid voltage older than battery_timeout_s
  kDisarmed,        // a motor at or below disarmed_pwm_max_us (0, 900 us, ...)
  kTooFewChannels,  // RCOut shorter than the highest motor channel
  kTimeBackwards,   // RCOut stamp older than the previous accepted one
  kOutsideDomain,   // outside the model's domain and the model says reject
  kNonFiniteEstimate,  // the model gives NaN or infinity (a rational surface extrapolated to its pole)
};
constexpr int kRejectionCount = 11;
const char* rejectionName(Rejection rejection);

// The last refusal with what it was about, turned into text only when someone asks.
struct RejectionDetail {
  Rejection reason = Rejection::kNone;
  int channel = 0;     // 1-based, for kDisarmed
  double value = 0.0;  // offending value (voltage, PWM, channel count, seconds)
  double limit = 0.0;  // what it was checked against
};
std::string describe(const RejectionDetail& detail);

struct MotorOutput {
  int channel = 0;
  double pwm_us = 0.0;
  OperatingPoint estimate;
};

struct Totals {
  double voltage_v = 0.0;
  double thrust_n = 0.0;
  double vertical_thrust_n = 0.0;
  double current_a = 0.0;
  double power_w = 0.0;
  double efficiency_n_per_w = 0.0;
  double mass_kg = 0.0;
  double thrust_centre_x_m = 0.0;  // NaN without vehicle geometry
  double thrust_centre_y_m = 0.0;
  int motors_out_of_domain = 0;
};

struct EstimatorOutput {
  double stamp_s = 0.0;
  std::vector<MotorOutput> motors;  // sized once, one per rotor
  Totals totals;
  HoverVerdict hover;
  MassEstimate payload;
};

struct EstimatorCounters {
  std::array<std::uint64_t, kRejectionCount> rejected{};
  std::uint64_t accepted = 0;
  std::uint64_t motor_samples = 0;
  std::uint64_t motor_samples_outside_domain = 0;
  std::uint64_t clock_resets = 0;
};

// Answer of tare(): the new empty mass, or why there is none.
struct TareResult {
  bool ok = false;
  double empty_mass_kg = 0.0;
  std::string message;
};

// The whole onboard estimation, free of ROS: inputs in, estimates out. `receipt_s` is the time
// an input arrived on the estimator's clock (ROS time, simulated when replaying a bag); it drives
// staleness. Stamps are the inputs' own header times. Evaluating motor outputs allocates nothing.
class Estimator {
 public:
  // Throws ConfigError if the configuration does not fit the vehicle.
  Estimator(PropulsionModel model, Vehicle vehicle, EstimatorConfig config);

  Rejection addBattery(double receipt_s, double voltage_v);
  // Orientation rotates body into the world (ENU); acceleration is the IMU's specific force in
  // the body frame (about +9.81 m/s^2 on z at rest), as MAVROS publishes them.
  Rejection addImu(double receipt_s, const Eigen::Quaterniond& orientation, const Eigen::Vector3d& specific_force);
  Rejection addVerticalSpeed(double receipt_s, double vertical_speed_m_s);

  // One RCOut message: PWM of all channels (0-based array of the message's channels). Returns
  // kNone and fills output(), or the reason nothing was computed.
  Rejection addMotorOutputs(double stamp_s, double receipt_s, const std::uint16_t* channels, std::size_t count);

  const EstimatorOutput& output() const { return output_; }
  const EstimatorCounters& counters() const { return counters_; }
  const RejectionDetail& lastRejection() const { return last_rejection_; }
  // Seconds since the newest valid voltage at `now_s`; infinity before any.
  double batteryAge(double now_s) const;

  // Records the current hover average as the empty mass, or refuses when not hovering.
  TareResult tare();
  // Sets the empty mass from elsewhere (a tare file, a parameter, the URDF).
  void setEmptyMass(double mass_kg, EmptyMassSource source);
  // Clears the windows and the tare; the configured empty mass (parameter or URDF) applies again.
  void reset();
  std::string describeHover() const;

  const PropulsionModel& model() const { return model_; }
  const Vehicle& vehicle() const { return vehicle_; }
  const EstimatorConfig& config() const { return config_; }

 private:
  Rejection reject(Rejection reason, int channel = 0, double value = 0.0, double limit = 0.0);
  void checkClock(double receipt_s);
  void clearWindows();

  PropulsionModel model_;
  Vehicle vehicle_;
  EstimatorConfig config_;
  std::optional<double> configured_empty_mass_kg_;
  EmptyMassSource configured_source_ = EmptyMassSource::kNone;

  HoverDetector hover_;
  PayloadEstimator payload_;
  VerticalAccelerationFilter accel_filter_;

  double voltage_v_ = 0.0;
  double voltage_receipt_s_ = 0.0;
  bool have_voltage_ = false;
  Eigen::Matrix3d body_to_world_ = Eigen::Matrix3d::Identity();
  double imu_receipt_s_ = 0.0;
  bool have_imu_ = false;
  double vertical_speed_m_s_ = 0.0;
  double velocity_receipt_s_ = 0.0;
  bool have_velocity_ = false;
  double last_stamp_s_ = 0.0;
  bool have_stamp_ = false;
  double last_receipt_s_ = 0.0;

  std::vector<OperatingPoint> scratch_;  // this message's motors, committed to output_ once all are valid
  EstimatorOutput output_;
  EstimatorCounters counters_;
  RejectionDetail last_rejection_;
};

}  // namespace propulsion_estimator
