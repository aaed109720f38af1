#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace propulsion_estimator {
namespace sim {

/// @file
/// What a simulated flight emits, message by message, in SI units and the frames MAVROS uses:
/// ENU world ("map", origin at base_link's start position), FLU body ("base_link"). Times are
/// seconds of simulated time from the first message. Each reading carries the standard deviation
/// of its noise for the message's covariance or variance fields.

/// /mavros/rc/out: the pulse width in us of each output channel.
struct RcOutSample {
  double time_s = 0.0;  ///< s
  std::vector<std::uint16_t> channels;  ///< motor k on channel k (1-based), unused channels 0
};

/// /mavros/battery: terminal voltage in V, current in A and remaining charge.
struct BatterySample {
  double time_s = 0.0;  ///< s
  double voltage_v = 0.0;   ///< at the battery's terminals
  double current_a = 0.0;   ///< sign as the autopilot reports it through MAVROS (PX4: negative when discharging)
  double percentage = 0.0;  ///< 0..1
};

/// /mavros/imu/data: orientation, body rates in rad/s and specific force in m/s^2, with their noise.
struct ImuSample {
  double time_s = 0.0;  ///< s
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< rotates body (FLU) into world (ENU)
  Eigen::Vector3d angular_velocity_rad_s = Eigen::Vector3d::Zero();    ///< body
  Eigen::Vector3d linear_acceleration_m_s2 = Eigen::Vector3d::Zero();  ///< specific force, body (+g at rest)
  /// Standard deviations of the noise of orientation (rad), angular velocity (rad/s) and
  /// acceleration (m/s^2).
  ///@{
  double orientation_sigma_rad = 0.0;
  double angular_velocity_sigma_rad_s = 0.0;
  double linear_acceleration_sigma_m_s2 = 0.0;
  ///@}
};

/// /mavros/local_position/pose: base_link's position in m and orientation in the world frame.
struct PoseSample {
  double time_s = 0.0;  ///< s
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< base_link, world
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< rotates body into world
};

/// /mavros/local_position/velocity_local: linear (m/s) and angular (rad/s) velocity, world frame.
struct VelocitySample {
  double time_s = 0.0;  ///< s
  Eigen::Vector3d linear_m_s = Eigen::Vector3d::Zero();     ///< world
  Eigen::Vector3d angular_rad_s = Eigen::Vector3d::Zero();  ///< world
};

/// A scalar reading: static pressure (Pa), air or motor temperature (deg C).
struct ScalarSample {
  double time_s = 0.0;  ///< s
  double value = 0.0;  ///< Pa or deg C
  double sigma = 0.0;  ///< standard deviation of its noise, same unit
  std::string frame_id;  ///< the hottest motor's link for the motor temperature, base_link otherwise
};

/// /mavros/rangefinder/rangefinder: distance to the ground in m, with the sensor's limits.
struct RangeSample {
  double time_s = 0.0;  ///< s
  double range_m = 0.0;  ///< -inf below min_range_m, +inf beyond max_range_m (REP-117)
  double min_range_m = 0.0;  ///< m, the sensor's nearest
  double max_range_m = 0.0;  ///< m, the sensor's farthest
  double field_of_view_rad = 0.0;  ///< rad
};

/// One ESC's telemetry packet as the autopilot forwards it (BLHeli_32/KISS/AM32 through ArduPilot's
/// ESC_TELEMETRY_x_TO_y or PX4's ESC_STATUS). A packet lost on the ESC's wire leaves the previous
/// one in place: the autopilot sends its last values again, with `count` unchanged.
struct EscReading {
  double rpm = 0.0;  ///< mechanical rotor speed, rpm (the ESC's electrical rpm over its pole pairs)
  double current_a = 0.0;  ///< A, the ESC's own current sensor
  double voltage_v = 0.0;  ///< V at the ESC's input, its own divider
  double temperature_c = 0.0;  ///< deg C, the ESC's
  std::uint16_t count = 0;  ///< packets received from this ESC (wraps)
};

/// /mavros/esc_telemetry (ArduPilot, mavros_msgs/ESCTelemetry) or /mavros/esc_status (PX4,
/// mavros_msgs/ESCStatus): one reading per motor, in motor order.
struct EscTelemetrySample {
  double time_s = 0.0;  ///< s
  bool px4 = true;  ///< PX4's ESCStatus, else ArduPilot's ESCTelemetry
  std::vector<EscReading> escs;  ///< one per motor
};

/// Per-motor truth.
struct MotorTruth {
  double pwm_us = 0.0;  ///< us
  double thrust_n = 0.0;   ///< force on the airframe along the rotor axis, all effects included
  double current_a = 0.0;  ///< ESC input current
  double power_w = 0.0;    ///< ESC input power
  double rpm = 0.0;  ///< rotor speed, rpm
  /// The inflow effects' thrust factors at the rotor's speed: the climb's, and the ground's on top
  /// of it (thrust = the propeller's static thrust x climb x ground; 1 when off).
  ///@{
  double ground_effect_factor = 1.0;
  double climb_factor = 1.0;
  ///@}
  double winding_temperature_c = 0.0;  ///< deg C
  bool in_bench_range = false;  ///< pulse width within the parameter file's bench sweep range
};

/// What a real flight cannot measure, for tests and the gap diagnosis.
struct TruthSample {
  double time_s = 0.0;  ///< s
  double total_mass_kg = 0.0;  ///< vehicle plus payload
  double payload_mass_kg = 0.0;  ///< kg, hanging on the cable
  double cable_tension_n = 0.0;  ///< 0 while the payload rests on the ground
  double height_m = 0.0;         ///< base_link above the ground
  double vertical_speed_m_s = 0.0;  ///< m/s, base_link, up positive
  double air_density_kg_m3 = 0.0;  ///< kg/m^3, the flight's air
  double density_ratio = 1.0;      ///< flight air over bench air
  double battery_voltage_v = 0.0;  ///< at the terminals, without sensor noise
  double esc_voltage_v = 0.0;      ///< after the supply path
  double battery_current_a = 0.0;  ///< A drawn from the battery, true, positive when discharging
  double climb_factor = 1.0;  ///< summed rotor thrust with the climb's inflow over without, at the rotors' speeds
  double thrust_loss_factor = 1.0;  ///< airframe thrust over the rotors' (1 - thrust_loss fraction)
  std::vector<MotorTruth> motors;  ///< one per rotor
};

/// Receiver of a simulated flight: the ROS layer writes a bag, tests record.
class FlightSink {
 public:
  virtual ~FlightSink() = default;
  /// One message of each stream, in the order the simulation emits them at each instant.
  ///@{
  virtual void rcOut(const RcOutSample& sample) = 0;
  virtual void battery(const BatterySample& sample) = 0;
  virtual void imu(const ImuSample& sample) = 0;
  virtual void pose(const PoseSample& sample) = 0;
  virtual void velocity(const VelocitySample& sample) = 0;
  virtual void staticPressure(const ScalarSample& sample) = 0;
  virtual void airTemperature(const ScalarSample& sample) = 0;
  virtual void rangefinder(const RangeSample& sample) = 0;
  virtual void motorTemperature(const ScalarSample& sample) = 0;
  virtual void truth(const TruthSample& sample) = 0;
  ///@}
  /// ESC telemetry (FlightSensorParams::esc_telemetry_rate_hz); a sink whose format does not
  /// carry it ignores it.
  virtual void escTelemetry(const EscTelemetrySample& /*sample*/) {}
};

}  // namespace sim
}  // namespace propulsion_estimator
