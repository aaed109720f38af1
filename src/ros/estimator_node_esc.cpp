// estimator_node's ESC telemetry (issue 21): the two MAVROS topics in, measured beside modelled on
// ~motors, the session's live model check on /diagnostics and ~capability.
#include "propulsion_estimator/ros/estimator_node.h"

namespace propulsion_estimator {

void EstimatorNode::setUpEscTelemetry(ros::NodeHandle& input_nh, const ros::TransportHints& hints) {
  const auto subscribe = [&](const std::string& topic, ros::Subscriber* subscriber) {
    if (topic.empty()) return;
    *subscriber = input_nh.subscribe<topic_tools::ShapeShifter>(
        topic, 20, [this, topic](const topic_tools::ShapeShifter::ConstPtr& message) { onEscTelemetry(message, topic); },
        ros::VoidConstPtr(), hints);
  };
  subscribe(params_.esc_telemetry_topic, &esc_telemetry_sub_);
  subscribe(params_.esc_status_topic, &esc_status_sub_);
  esc_inputs_.topics = (params_.esc_telemetry_topic.empty() ? std::string("-") : params_.esc_telemetry_topic) + ", " +
                       (params_.esc_status_topic.empty() ? std::string("-") : params_.esc_status_topic);
  diagnostics_.add("ESC telemetry", [this](diagnostic_updater::DiagnosticStatusWrapper& status) {
    copy(judgeEscTelemetry(*session_, ros::Time::now().toSec(), esc_inputs_), &status);
  });
}

void EstimatorNode::onEscTelemetry(const topic_tools::ShapeShifter::ConstPtr& message, const std::string& topic) {
  const std::lock_guard<std::mutex> lock(state_);
  ++esc_inputs_.received;
  if (!esc_decoder_.decode(*message, &esc_message_, &esc_inputs_.last_error)) {
    ++esc_inputs_.undecodable;
    ROS_ERROR_STREAM_THROTTLE(5.0, topic << ": " << esc_inputs_.last_error);
    return;
  }
  session_->addEscTelemetry(ros::Time::now().toSec(), esc_message_);
}

void EstimatorNode::fillMeasured(double now_s) {
  for (std::size_t i = 0; i < motors_msg_.motors.size(); ++i) {
    const MotorCheck check = session_->modelCheck().motor(i, now_s);
    MotorEstimate& m = motors_msg_.motors[i];
    m.measured_rpm = check.measured_rpm;
    m.measured_current_a = check.measured_current_a;
    m.rpm_ratio = check.rpm_ratio;
    m.current_ratio = check.current_ratio;
  }
}

void EstimatorNode::fillModelCheck(const CapabilityState& state, Capability* msg) {
  const ModelCheckReport& report = state.model_check;
  msg->model_check_verdict = modelCheckVerdictName(report.verdict);
  msg->model_check_note = report.note;
  msg->model_check_flagged_channel = static_cast<std::uint8_t>(report.flagged_channel);
  for (const MotorCheck& m : report.motors) {
    msg->model_check_channels.push_back(static_cast<std::uint8_t>(m.channel));
    msg->motor_rpm_ratio.push_back(m.hover_rpm_ratio);
    msg->motor_current_ratio.push_back(m.hover_current_ratio);
  }
  msg->supply_resistance_ohm = report.supply_resistance_ohm;
  msg->supply_resistance_std_ohm = report.supply_resistance_std_ohm;
  msg->supply_resistance_applied = !std::isnan(state.supply_applied_ohm);
  msg->mass_view = state.rpm_mass_view ? "rpm" : "pwm";
  msg->rpm_view_mass_kg = state.rpm_view_mass_kg;
}

}  // namespace propulsion_estimator
