#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/TwistStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/Imu.h>
#include <std_srvs/Trigger.h>
#include <topic_tools/shape_shifter.h>

#include "propulsion_estimator/MotorEstimates.h"
#include "propulsion_estimator/PayloadEstimate.h"
#include "propulsion_estimator/PropulsionTotals.h"
#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/ros/estimator_params.h"
#include "propulsion_estimator/ros/rcout_codec.h"

namespace propulsion_estimator {

// estimator_node: adapts topics, services and diagnostics to the core Estimator. Nothing is
// computed here.
class EstimatorNode {
 public:
  // Throws ConfigError for bad parameters, model, URDF or tare file.
  EstimatorNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

 private:
  // Messages received per input since the last diagnostics update, for rates.
  enum Input { kRcOut = 0, kBattery, kImu, kVelocity, kInputCount };

  void onRcOut(const topic_tools::ShapeShifter::ConstPtr& message);
  void onBattery(const sensor_msgs::BatteryState::ConstPtr& message);
  void onImu(const sensor_msgs::Imu::ConstPtr& message);
  void onVelocity(const geometry_msgs::TwistStamped::ConstPtr& message);
  void logRejection(Rejection rejection);
  void publish();

  bool onTare(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool onDetectHover(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool onReset(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);

  void diagnoseInputs(diagnostic_updater::DiagnosticStatusWrapper& status);
  void diagnoseMotorOutputs(diagnostic_updater::DiagnosticStatusWrapper& status);
  void diagnoseDomain(diagnostic_updater::DiagnosticStatusWrapper& status);
  void diagnosePayload(diagnostic_updater::DiagnosticStatusWrapper& status);

  EstimatorNodeParams params_;
  std::string model_fingerprint_;
  std::unique_ptr<Estimator> estimator_;

  ros::Subscriber rc_out_sub_, battery_sub_, imu_sub_, velocity_sub_;
  ros::Publisher motors_pub_, totals_pub_, payload_pub_;
  ros::ServiceServer tare_srv_, detect_hover_srv_, reset_srv_;
  diagnostic_updater::Updater diagnostics_;

  RcOutDecoder decoder_;
  RcOutMessage rc_out_;
  std::string decode_error_;
  MotorEstimates motors_msg_;
  PropulsionTotals totals_msg_;
  PayloadEstimate payload_msg_;

  // Counts at a diagnostics task's previous run, from which it derives rates and fractions.
  struct Snapshot {
    ros::Time time;
    std::array<std::uint64_t, kInputCount> received{};
    EstimatorCounters counters;
  };
  Snapshot takeSnapshot() const;

  ros::Timer diagnostics_timer_;
  std::array<std::uint64_t, kInputCount> received_{};
  Snapshot inputs_before_, outputs_before_, domain_before_;
  std::uint64_t imu_without_orientation_ = 0;
  Rejection last_rc_out_verdict_ = Rejection::kNone;
  std::uint64_t rc_out_undecodable_ = 0;  // wrong type or malformed: never reaches the estimator
  std::uint64_t rc_out_undecodable_before_ = 0;
};

}  // namespace propulsion_estimator
