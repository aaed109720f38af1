#pragma once

#include <memory>
#include <mutex>
#include <string>

#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/TwistStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/Range.h>
#include <sensor_msgs/Temperature.h>
#include <std_srvs/Trigger.h>
#include <topic_tools/shape_shifter.h>

#include "propulsion_estimator/Capability.h"
#include "propulsion_estimator/MotorEstimates.h"
#include "propulsion_estimator/PayloadEstimate.h"
#include "propulsion_estimator/PropulsionTotals.h"
#include "propulsion_estimator/onboard/esc_telemetry_health.h"
#include "propulsion_estimator/onboard/health_summary.h"
#include "propulsion_estimator/onboard/onboard_session.h"
#include "propulsion_estimator/onboard/pack_file_keeper.h"
#include "propulsion_estimator/onboard/rate_limiter.h"
#include "propulsion_estimator/ros/estimator_params.h"
#include "propulsion_estimator/codecs/esc_telemetry_codec.h"
#include "propulsion_estimator/ros/inline_callback_queue.h"
#include "propulsion_estimator/codecs/rcout_codec.h"

namespace propulsion_estimator {

/// estimator_node: adapts topics, services and diagnostics to the onboard session
/// (onboard/onboard_session.h), which computes and judges everything: the node subscribes, decodes,
/// hands each reading over, and copies the session's answers into messages and diagnostics.
///
/// Threads: the subscriptions' callbacks run in roscpp's network thread as each message is read
/// (InlineCallbackQueue); timers and services run in the thread that spins the global queue
/// (ros::spin()). The two share the estimator under one mutex.
class EstimatorNode {
 public:
  /// Throws ConfigError for bad parameters, model or URDF. A tare file that cannot be read is moved
  /// aside and named on the Tare file diagnostic; the node starts without it.
  EstimatorNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

 private:
  void onRcOut(const topic_tools::ShapeShifter::ConstPtr& message);
  void onBattery(const sensor_msgs::BatteryState::ConstPtr& message);
  void onImu(const sensor_msgs::Imu::ConstPtr& message);
  void onVelocity(const geometry_msgs::TwistStamped::ConstPtr& message);
  void onInput(input::Scalar scalar, double value);  ///< a scalar input's reading, in its spec's unit
  void onRange(const sensor_msgs::Range::ConstPtr& message);
  /// ESC telemetry (estimator_node_esc.cpp): mavros_msgs/ESCTelemetry or ESCStatus from `topic`.
  void onEscTelemetry(const topic_tools::ShapeShifter::ConstPtr& message, const std::string& topic);
  /// Subscribes to the ESC telemetry topics that are not "" and adds the "ESC telemetry" diagnostic.
  void setUpEscTelemetry(ros::NodeHandle& input_nh, const ros::TransportHints& hints);
  /// The measured rpm and current beside the modelled ones on ~motors (NaN when absent or stale).
  void fillMeasured(double now_s);
  /// The model check's fields of ~capability.
  static void fillModelCheck(const CapabilityState& state, Capability* msg);
  /// A health verdict of the session as a diagnostic status.
  static void copy(const HealthStatus& health, diagnostic_updater::DiagnosticStatusWrapper* status);
  /// Logs which references the motor checks judge against.
  void logMotorChecks() const;
  /// Subscribes to the scalar inputs the session reads (and refuses a topic an effect needs set
  /// to ""); logs which effects apply with which parameters.
  void subscribeEffectSignals(ros::NodeHandle& input_nh, const ros::NodeHandle& private_nh,
                              const ros::TransportHints& hints);
  /// Applies the tare file of an earlier run, if any and taken with this model.
  void loadTare();
  /// The pack file of pack `pack_id`, read into the session (`before_start`: into the parameters
  /// the session is made with).
  void identifyPack(const std::string& pack_id, bool before_start);
  /// After a battery message: a finished flight's record written.
  void learnPack();
  // One pack-file line to the log, a WARN when the file was refused or is not written.
  static void logPackFile(const std::string& line, bool warn);
  // The Pack file diagnostic: the keeper's note, what a landed flight still waits for.
  void packFileStatus(diagnostic_updater::DiagnosticStatusWrapper* status) const;
  /// Subscribes to `scalar` on `topic`, decoding its ScalarSpec's message.
  ros::Subscriber subscribeInput(ros::NodeHandle& input_nh, input::Scalar scalar, const std::string& topic,
                                 const ros::TransportHints& hints);
  /// What the Tare file diagnostic says (and the log, once).
  void setTareFileStatus(std::uint8_t level, const std::string& message);
  void logRejection(Rejection rejection);
  void publish();
  /// ~capability, from its own timer at capability/rate_hz.
  void publishCapability();

  bool onTare(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool onDetectHover(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool onReset(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);

  HealthSnapshot takeSnapshot() const;

  EstimatorNodeParams params_;
  std::string model_fingerprint_;
  std::unique_ptr<OnboardSession> session_;
  PackFileKeeper pack_file_;  // capability/battery/pack_file across the run
  EscTelemetryDecoder esc_decoder_;
  EscTelemetry esc_message_;
  EscInputActivity esc_inputs_;
  bool supply_logged_ = false;  ///< the supply resistance's first application was logged
  CapabilityState last_capability_;

  ros::Publisher motors_pub_, totals_pub_, payload_pub_, capability_pub_;
  ros::ServiceServer tare_srv_, detect_hover_srv_, reset_srv_;
  diagnostic_updater::Updater diagnostics_;
  std::uint8_t tare_file_level_ = diagnostic_msgs::DiagnosticStatus::OK;
  std::string tare_file_message_;

  RateLimiter publish_limiter_;
  RcOutDecoder decoder_;
  RcOutMessage rc_out_;
  MotorEstimates motors_msg_;
  PropulsionTotals totals_msg_;
  PayloadEstimate payload_msg_;

  ros::Timer diagnostics_timer_, capability_timer_;
  InputActivity inputs_;
  /// Counts at each diagnostics task's previous run, from which it derives rates and fractions.
  HealthSnapshot inputs_before_, outputs_before_, domain_before_, effects_before_;

  /// What the subscriptions' callbacks (network thread) share with timers and services (spinner).
  std::mutex state_;
  InlineCallbackQueue input_queue_;
  /// Declared last, so destroyed first: a subscriber's destruction waits for its running callback,
  /// which uses everything above.
  ros::Subscriber rc_out_sub_, battery_sub_, imu_sub_, velocity_sub_;
  input::PerScalar<ros::Subscriber> input_subs_;  ///< by input::index
  ros::Subscriber esc_telemetry_sub_, esc_status_sub_;
};

}  // namespace propulsion_estimator
