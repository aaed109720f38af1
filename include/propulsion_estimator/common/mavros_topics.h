#pragma once

namespace propulsion_estimator {

/// The topics a flight's signals arrive on, as MAVROS names them (the scalar inputs' are in
/// input_signal.h): the node's default inputs, the
/// simulator's bag topics and the flight bag reader's defaults, spelt here only.
///@{
constexpr const char* kRcOutTopic = "/mavros/rc/out";                                   ///< mavros_msgs/RCOut
constexpr const char* kBatteryTopic = "/mavros/battery";                                ///< sensor_msgs/BatteryState
constexpr const char* kImuTopic = "/mavros/imu/data";                                   ///< sensor_msgs/Imu
constexpr const char* kPoseTopic = "/mavros/local_position/pose";                       ///< geometry_msgs/PoseStamped
constexpr const char* kVelocityTopic = "/mavros/local_position/velocity_local";         ///< geometry_msgs/TwistStamped
constexpr const char* kEscTelemetryTopic = "/mavros/esc_telemetry";  ///< mavros_msgs/ESCTelemetry (ArduPilot)
constexpr const char* kEscStatusTopic = "/mavros/esc_status";        ///< mavros_msgs/ESCStatus (PX4)
///@}

}  // namespace propulsion_estimator
