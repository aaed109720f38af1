// estimator_node's ESC telemetry (issue 21): the two MAVROS topics in, measured beside modelled on
// ~motors, the live model check on /diagnostics and ~capability, the supply resistance applied.
#include <cmath>
#include <cstdio>

#include "propulsion_estimator/ros/estimator_node.h"

#include "propulsion_estimator/common/config_error.h"

namespace propulsion_estimator {
namespace {

std::string formatted(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

}  // namespace

void EstimatorNode::setUpEscTelemetry(ros::NodeHandle& input_nh, const ros::TransportHints& hints) {
  const auto subscribe = [&](const std::string& topic, ros::Subscriber* subscriber) {
    if (topic.empty()) return;
    *subscriber = input_nh.subscribe<topic_tools::ShapeShifter>(
        topic, 20, [this, topic](const topic_tools::ShapeShifter::ConstPtr& message) { onEscTelemetry(message, topic); },
        ros::VoidConstPtr(), hints);
  };
  subscribe(params_.esc_telemetry_topic, &esc_telemetry_sub_);
  subscribe(params_.esc_status_topic, &esc_status_sub_);
  // The supply_resistance effect reads the battery current.
  if (params_.esc_telemetry.apply_supply_resistance) pass_battery_current_ = true;
  const std::optional<RpmThrust>& rpm_thrust = estimator_->model().rpmThrust();
  if (rpm_thrust) rpm_view_.emplace(*rpm_thrust, params_.estimator.payload.averaging_window_s);
  if (params_.mass_view == "rpm" && !rpm_thrust) {
    throw ConfigError(ros::NodeHandle("~").resolveName("esc_telemetry/mass_view") + ": rpm, but " + params_.model +
                      " has no thrust_from_rpm (fit_surfaces writes it from bench logs with an rpm column)");
  }
  diagnostics_.add("ESC telemetry", [this](diagnostic_updater::DiagnosticStatusWrapper& status) {
    judgeEscTelemetry(model_check_->report(ros::Time::now().toSec()), &status);
  });
}

void EstimatorNode::onEscTelemetry(const topic_tools::ShapeShifter::ConstPtr& message, const std::string& topic) {
  const std::lock_guard<std::mutex> lock(state_);
  ++esc_received_;
  if (!esc_decoder_.decode(*message, &esc_message_, &esc_last_error_)) {
    ++esc_undecodable_;
    ROS_ERROR_STREAM_THROTTLE(5.0, topic << ": " << esc_last_error_);
    return;
  }
  model_check_->addTelemetry(ros::Time::now().toSec(), esc_message_);
}

void EstimatorNode::checkModel(double now_s) {
  const EstimatorOutput& output = estimator_->output();
  model_check_->addEstimate(now_s, output);
  // The air density is prepared only for a hover, the one sample the view takes.
  if (rpm_view_) {
    rpm_view_->add(now_s, output, *model_check_,
                   output.hover.hovering ? estimator_->effectSignals(now_s).air_density_kg_m3 : kNaN);
  }
}

bool EstimatorNode::rpmViewInUse(double now_s) const {
  if (params_.mass_view != "rpm" || !rpm_view_ || std::isnan(rpm_view_->massKg())) return false;
  for (std::size_t k = 0; k < motors_msg_.motors.size(); ++k) {
    if (std::isnan(model_check_->motor(k, now_s).measured_rpm)) return false;
  }
  return true;
}

const EstimatorOutput& EstimatorNode::capabilityInput(double now_s) {
  if (!rpmViewInUse(now_s)) return estimator_->output();
  rpm_output_ = estimator_->output();
  rpm_output_.payload.total_mass_kg = rpm_view_->massKg();
  rpm_output_.payload.window_s = rpm_view_->hoverS();
  return rpm_output_;
}

void EstimatorNode::fillMeasured(double now_s) {
  for (std::size_t i = 0; i < motors_msg_.motors.size(); ++i) {
    const MotorCheck check = model_check_->motor(i, now_s);
    MotorEstimate& m = motors_msg_.motors[i];
    m.measured_rpm = check.measured_rpm;
    m.measured_current_a = check.measured_current_a;
    m.rpm_ratio = check.rpm_ratio;
    m.current_ratio = check.current_ratio;
  }
}

void EstimatorNode::applySupplyResistance() {
  if (!params_.esc_telemetry.apply_supply_resistance) return;
  const double ohm = model_check_->supplyResistanceOhm();
  if (std::isnan(ohm)) return;
  // A new model only when the estimate has moved by more than its own resolution (1 mOhm or 5 %).
  if (!std::isnan(supply_applied_ohm_) &&
      std::fabs(ohm - supply_applied_ohm_) < std::max(0.001, 0.05 * supply_applied_ohm_)) {
    return;
  }
  estimator_->setEffect(effects::Kind::kSupplyResistance, ohm);
  if (std::isnan(supply_applied_ohm_)) ROS_INFO_STREAM("supply_resistance effect applied from ESC telemetry: " << ohm << " ohm");
  supply_applied_ohm_ = ohm;
}

void EstimatorNode::judgeEscTelemetry(const ModelCheckReport& report,
                                      diagnostic_updater::DiagnosticStatusWrapper* status) const {
  using diagnostic_msgs::DiagnosticStatus;
  const std::size_t motors = report.motors.size();
  status->add("topics", (params_.esc_telemetry_topic.empty() ? std::string("-") : params_.esc_telemetry_topic) + ", " +
                            (params_.esc_status_topic.empty() ? std::string("-") : params_.esc_status_topic));
  status->add("messages", esc_received_);
  status->add("undecodable", esc_undecodable_);
  status->add("fresh_motors", std::to_string(report.fresh_motors) + " of " + std::to_string(motors));
  status->add("verdict", modelCheckVerdictName(report.verdict));
  status->add("flagged_channel", report.flagged_channel);
  for (const MotorCheck& m : report.motors) {
    status->add("channel " + std::to_string(m.channel) + " hover rpm / current ratio",
                formatted("%.3f", m.hover_rpm_ratio) + " / " + formatted("%.3f", m.hover_current_ratio));
  }
  status->add("supply_resistance_ohm", formatted("%.4f", report.supply_resistance_ohm) + " +- " +
                                           formatted("%.4f", report.supply_resistance_std_ohm));
  status->add("supply_resistance_applied", std::isnan(supply_applied_ohm_) ? std::string("no")
                                                                          : formatted("%.4f ohm", supply_applied_ohm_));
  status->add("advice", modelCheckAdvice(report.verdict));
  const double now = ros::Time::now().toSec();
  status->add("mass_view", rpmViewInUse(now) ? std::string("rpm")
                           : params_.mass_view == "rpm"
                               ? std::string("pwm (rpm chosen: no rpm-view mass yet or telemetry stale)")
                               : std::string("pwm"));
  status->add("rpm_view_mass_kg", rpm_view_ ? formatted("%.3f", rpm_view_->massKg()) : std::string("no thrust_from_rpm"));
  if (rpm_view_ && rpm_view_->atBenchAir()) {
    status->add("rpm_view_air", "the bench's air density (no static pressure and air temperature): off by the "
                                "density ratio on another day's air");
  }
  status->add("pwm_view_mass_kg", formatted("%.3f", estimator_->output().payload.total_mass_kg));
  if (!report.telemetry_seen) {
    status->summary(DiagnosticStatus::OK, esc_undecodable_ > 0
                                              ? "no usable ESC telemetry (" + esc_last_error_ + "): nothing measured, model check off"
                                              : "no ESC telemetry: nothing measured, model check off, estimates unchanged");
    return;
  }
  if (report.fresh_motors < static_cast<int>(motors)) {
    status->summary(DiagnosticStatus::WARN, "ESC telemetry stale on " + std::to_string(motors - report.fresh_motors) +
                                                " of " + std::to_string(motors) +
                                                " motors: measured values NaN, averages held, estimates unchanged; " +
                                                report.note);
    return;
  }
  const bool flagged = report.verdict == ModelCheckVerdict::kPropeller ||
                       report.verdict == ModelCheckVerdict::kMotorEsc || report.verdict == ModelCheckVerdict::kSupply;
  status->summary(flagged ? DiagnosticStatus::WARN : DiagnosticStatus::OK,
                  report.note + (flagged ? std::string(": ") + modelCheckAdvice(report.verdict) : std::string()));
}

void EstimatorNode::fillModelCheck(double now_s, Capability* msg) {
  const ModelCheckReport report = model_check_->report(now_s);
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
  msg->supply_resistance_applied = !std::isnan(supply_applied_ohm_);
  msg->mass_view = rpmViewInUse(now_s) ? "rpm" : "pwm";
  msg->rpm_view_mass_kg = rpm_view_ ? rpm_view_->massKg() : kNaN;
}

}  // namespace propulsion_estimator
