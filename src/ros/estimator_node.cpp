#include "propulsion_estimator/ros/estimator_node.h"

#include <cmath>
#include <sstream>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/estimation/tare_file.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"

namespace propulsion_estimator {
namespace {

using diagnostic_msgs::DiagnosticStatus;

Vehicle loadVehicle(const ros::NodeHandle& nh, const EstimatorNodeParams& params) {
  if (!params.urdf_file.empty()) {
    ROS_INFO_STREAM("vehicle from URDF file " << params.urdf_file);
    return loadVehicleUrdf(params.urdf_file);
  }
  std::string key, xml;
  if (nh.searchParam("robot_description", key) && nh.getParam(key, xml)) {
    ROS_INFO_STREAM("vehicle from parameter " << key);
    return vehicleFromUrdf(xml, key);
  }
  ROS_INFO_STREAM("no URDF: " << params.estimator.motor_channels.size()
                              << " rotors thrusting along +z at unknown positions (thrust centre not estimated)");
  return Vehicle::upwardRotors(static_cast<int>(params.estimator.motor_channels.size()));
}

double rate(std::uint64_t now, std::uint64_t before, double seconds) {
  return seconds > 0.0 ? static_cast<double>(now - before) / seconds : 0.0;
}

}  // namespace

EstimatorNode::EstimatorNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : params_(readEstimatorNodeParams(private_nh)), diagnostics_(nh, private_nh) {
  PropulsionModel model = loadModelFile(params_.model);
  model_fingerprint_ = modelFingerprint(model);
  const ModelMetadata& meta = model.metadata();
  ROS_INFO_STREAM("model " << params_.model << ": " << meta.esc << " + " << meta.motor << " + " << meta.propeller
                           << ", domain " << model.domain().pwm_min_us << "-" << model.domain().pwm_max_us << " us, "
                           << model.domain().voltage_min_v << "-" << model.domain().voltage_max_v
                           << " V, outside: " << outsideDomainName(model.domain().outside));
  Vehicle vehicle = loadVehicle(nh, params_);
  estimator_ = std::make_unique<Estimator>(std::move(model), std::move(vehicle), params_.estimator);

  if (!params_.tare_file.empty()) {
    if (const std::optional<TareRecord> tare = loadTareFile(params_.tare_file)) {
      if (tare->model_fingerprint == model_fingerprint_) {
        estimator_->setEmptyMass(tare->empty_mass_kg, EmptyMassSource::kTareFile);
        ROS_INFO_STREAM("empty mass " << tare->empty_mass_kg << " kg from tare file " << params_.tare_file);
      } else {
        ROS_WARN_STREAM("tare file " << params_.tare_file << " ignored: it was taken with another model (" << tare->model
                                     << ", fingerprint " << tare->model_fingerprint << ") than " << params_.model
                                     << " (fingerprint " << model_fingerprint_ << ")");
      }
    }
  }
  const MassEstimate& payload = estimator_->output().payload;
  ROS_INFO_STREAM("empty mass: " << (std::isnan(payload.empty_mass_kg) ? std::string("unknown until ~tare")
                                                                       : std::to_string(payload.empty_mass_kg) + " kg")
                                 << " (source: " << emptyMassSourceName(payload.empty_mass_source) << ")");

  const std::size_t motors = estimator_->vehicle().rotors.size();
  motors_msg_.motors.resize(motors);
  for (std::size_t i = 0; i < motors; ++i) {
    motors_msg_.motors[i].channel = static_cast<std::uint8_t>(params_.estimator.motor_channels[i]);
  }
  rc_out_.channels.reserve(32);

  motors_pub_ = private_nh.advertise<MotorEstimates>("motors", 10);
  totals_pub_ = private_nh.advertise<PropulsionTotals>("totals", 10);
  payload_pub_ = private_nh.advertise<PayloadEstimate>("payload", 10);
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  rc_out_sub_ = nh.subscribe(params_.rc_out_topic, 20, &EstimatorNode::onRcOut, this, hints);
  battery_sub_ = nh.subscribe(params_.battery_topic, 5, &EstimatorNode::onBattery, this, hints);
  if (!params_.imu_topic.empty()) imu_sub_ = nh.subscribe(params_.imu_topic, 20, &EstimatorNode::onImu, this, hints);
  if (!params_.velocity_topic.empty()) {
    velocity_sub_ = nh.subscribe(params_.velocity_topic, 20, &EstimatorNode::onVelocity, this, hints);
  }
  tare_srv_ = private_nh.advertiseService("tare", &EstimatorNode::onTare, this);
  detect_hover_srv_ = private_nh.advertiseService("detect_hover", &EstimatorNode::onDetectHover, this);
  reset_srv_ = private_nh.advertiseService("reset", &EstimatorNode::onReset, this);

  diagnostics_.setHardwareID(meta.esc + " / " + meta.motor + " / " + meta.propeller);
  diagnostics_.add("Inputs", this, &EstimatorNode::diagnoseInputs);
  diagnostics_.add("Motor outputs", this, &EstimatorNode::diagnoseMotorOutputs);
  diagnostics_.add("Model domain", this, &EstimatorNode::diagnoseDomain);
  diagnostics_.add("Payload", this, &EstimatorNode::diagnosePayload);
  inputs_before_ = outputs_before_ = domain_before_ = takeSnapshot();
  diagnostics_timer_ = nh.createTimer(ros::Duration(0.1), [this](const ros::TimerEvent&) { diagnostics_.update(); });
}

EstimatorNode::Snapshot EstimatorNode::takeSnapshot() const {
  return Snapshot{ros::Time::now(), received_, estimator_->counters()};
}

void EstimatorNode::onRcOut(const topic_tools::ShapeShifter::ConstPtr& message) {
  ++received_[kRcOut];
  if (!decoder_.decode(*message, &rc_out_, &decode_error_)) {
    ++rc_out_undecodable_;
    ROS_ERROR_STREAM_THROTTLE(5.0, params_.rc_out_topic << ": " << decode_error_);
    return;
  }
  last_rc_out_verdict_ = estimator_->addMotorOutputs(rc_out_.header.stamp.toSec(), ros::Time::now().toSec(),
                                                      rc_out_.channels.data(), rc_out_.channels.size());
  if (last_rc_out_verdict_ != Rejection::kNone) {
    logRejection(last_rc_out_verdict_);
    return;
  }
  publish();
}

void EstimatorNode::onBattery(const sensor_msgs::BatteryState::ConstPtr& message) {
  ++received_[kBattery];
  logRejection(estimator_->addBattery(ros::Time::now().toSec(), message->voltage));
}

void EstimatorNode::onImu(const sensor_msgs::Imu::ConstPtr& message) {
  ++received_[kImu];
  // REP-145: a covariance of -1 says the orientation is not provided.
  if (message->orientation_covariance[0] == -1.0) {
    ++imu_without_orientation_;
    ROS_WARN_STREAM_THROTTLE(30.0, params_.imu_topic << " carries no orientation: tilt and acceleration not compensated");
    return;
  }
  const auto& q = message->orientation;
  const auto& a = message->linear_acceleration;
  logRejection(estimator_->addImu(ros::Time::now().toSec(), Eigen::Quaterniond(q.w, q.x, q.y, q.z),
                                  Eigen::Vector3d(a.x, a.y, a.z)));
}

void EstimatorNode::onVelocity(const geometry_msgs::TwistStamped::ConstPtr& message) {
  ++received_[kVelocity];
  logRejection(estimator_->addVerticalSpeed(ros::Time::now().toSec(), message->twist.linear.z));
}

void EstimatorNode::logRejection(Rejection rejection) {
  if (rejection == Rejection::kNone) return;
  if (rejection == Rejection::kDisarmed) {
    ROS_INFO_STREAM_THROTTLE(30.0, describe(estimator_->lastRejection()));
  } else {
    ROS_WARN_STREAM_THROTTLE(5.0, describe(estimator_->lastRejection()));
  }
}

void EstimatorNode::publish() {
  const EstimatorOutput& out = estimator_->output();
  const std_msgs::Header& header = rc_out_.header;

  motors_msg_.header = header;
  motors_msg_.voltage_v = out.totals.voltage_v;
  for (std::size_t i = 0; i < out.motors.size(); ++i) {
    MotorEstimate& m = motors_msg_.motors[i];
    const MotorOutput& o = out.motors[i];
    m.pwm_us = o.pwm_us;
    m.thrust_n = o.estimate.thrust_n;
    m.current_a = o.estimate.current_a;
    m.power_w = o.estimate.power_w;
    m.efficiency_n_per_w = o.estimate.efficiency_n_per_w;
    m.rpm = o.estimate.rpm;
    m.in_domain = o.estimate.in_domain;
  }
  motors_pub_.publish(motors_msg_);

  const Totals& t = out.totals;
  totals_msg_.header = header;
  totals_msg_.voltage_v = t.voltage_v;
  totals_msg_.thrust_n = t.thrust_n;
  totals_msg_.vertical_thrust_n = t.vertical_thrust_n;
  totals_msg_.current_a = t.current_a;
  totals_msg_.power_w = t.power_w;
  totals_msg_.efficiency_n_per_w = t.efficiency_n_per_w;
  totals_msg_.mass_kg = t.mass_kg;
  totals_msg_.thrust_centre_x_m = t.thrust_centre_x_m;
  totals_msg_.thrust_centre_y_m = t.thrust_centre_y_m;
  totals_msg_.motors_out_of_domain = static_cast<std::uint8_t>(t.motors_out_of_domain);
  totals_pub_.publish(totals_msg_);

  const MassEstimate& p = out.payload;
  payload_msg_.header = header;
  payload_msg_.state = payloadStateName(p.state);
  payload_msg_.hovering = p.hovering;
  payload_msg_.total_mass_kg = p.total_mass_kg;
  payload_msg_.mass_std_kg = p.mass_std_kg;
  payload_msg_.empty_mass_kg = p.empty_mass_kg;
  payload_msg_.empty_mass_source = emptyMassSourceName(p.empty_mass_source);
  payload_msg_.payload_mass_kg = p.payload_mass_kg;
  payload_msg_.window_s = p.window_s;
  payload_msg_.window_samples = p.window_samples;
  payload_pub_.publish(payload_msg_);
}

bool EstimatorNode::onTare(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  const TareResult tare = estimator_->tare();
  response.success = tare.ok;
  response.message = tare.message;
  if (tare.ok && !params_.tare_file.empty()) {
    try {
      saveTareFile(params_.tare_file, TareRecord{tare.empty_mass_kg, params_.model, model_fingerprint_});
      response.message += ", saved to " + params_.tare_file;
    } catch (const ConfigError& e) {
      response.message += std::string(", NOT persisted: ") + e.what();
    }
  }
  ROS_INFO_STREAM("~tare: " << response.message);
  return true;
}

bool EstimatorNode::onDetectHover(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  const EstimatorOutput& out = estimator_->output();
  response.success = out.hover.hovering;
  std::ostringstream message;
  message.precision(4);
  message << estimator_->describeHover();
  if (!std::isnan(out.payload.total_mass_kg)) {
    message << "; averaged mass " << out.payload.total_mass_kg << " kg (std " << out.payload.mass_std_kg << " kg, "
            << out.payload.window_samples << " samples over " << out.payload.window_s << " s)";
  }
  response.message = message.str();
  return true;
}

bool EstimatorNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  estimator_->reset();
  if (!params_.tare_file.empty()) removeTareFile(params_.tare_file);
  const MassEstimate& p = estimator_->output().payload;
  std::ostringstream message;
  message << "windows and tare cleared; empty mass now "
          << (std::isnan(p.empty_mass_kg) ? std::string("unknown") : std::to_string(p.empty_mass_kg) + " kg")
          << " (source: " << emptyMassSourceName(p.empty_mass_source) << ")";
  response.success = true;
  response.message = message.str();
  ROS_INFO_STREAM("~reset: " << response.message);
  return true;
}

void EstimatorNode::diagnoseInputs(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const Snapshot now = takeSnapshot();
  const double seconds = (now.time - inputs_before_.time).toSec();
  const char* names[kInputCount] = {"rc_out rate (Hz)", "battery rate (Hz)", "imu rate (Hz)", "velocity rate (Hz)"};
  for (int i = 0; i < kInputCount; ++i) status.add(names[i], rate(now.received[i], inputs_before_.received[i], seconds));
  const double rc_out_rate = rate(now.received[kRcOut], inputs_before_.received[kRcOut], seconds);
  const double age = estimator_->batteryAge(now.time.toSec());
  status.add("battery age (s)", age);
  status.add("imu messages without orientation", imu_without_orientation_);
  const double timeout = params_.estimator.battery_timeout_s;
  if (std::isinf(age)) {
    status.summary(DiagnosticStatus::ERROR, "estimates stopped: no valid battery voltage received on " +
                                                params_.battery_topic);
  } else if (age > timeout) {
    std::ostringstream message;
    message.precision(3);
    message << "estimates stopped: no battery voltage for " << age << " s (limit " << timeout << " s) on "
            << params_.battery_topic;
    status.summary(DiagnosticStatus::ERROR, message.str());
  } else if (now.received[kRcOut] == inputs_before_.received[kRcOut]) {
    status.summary(DiagnosticStatus::WARN, "no motor outputs on " + params_.rc_out_topic);
  } else if (rc_out_rate > params_.estimator.max_rate_hz) {
    std::ostringstream message;
    message.precision(3);
    message << params_.rc_out_topic << " at " << rc_out_rate << " Hz, above max_rate_hz "
            << params_.estimator.max_rate_hz << ": the hover and averaging windows cover less time than configured";
    status.summary(DiagnosticStatus::WARN, message.str());
  } else {
    status.summary(DiagnosticStatus::OK, "receiving");
  }
  inputs_before_ = now;
}

void EstimatorNode::diagnoseMotorOutputs(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const Snapshot now = takeSnapshot();
  const EstimatorCounters& c = now.counters;
  status.add("accepted", c.accepted);
  for (int r = 1; r < kRejectionCount; ++r) {
    status.add(std::string("rejected ") + rejectionName(static_cast<Rejection>(r)), c.rejected[r]);
  }
  status.add("rejected undecodable", rc_out_undecodable_);
  status.add("clock resets", c.clock_resets);
  status.add("last rejection", describe(estimator_->lastRejection()));
  if (rc_out_undecodable_ > 0) status.add("last decoding error", decode_error_);
  std::uint64_t new_problems = 0;
  for (int r = 1; r < kRejectionCount; ++r) {
    if (r != static_cast<int>(Rejection::kDisarmed)) new_problems += c.rejected[r] - outputs_before_.counters.rejected[r];
  }
  if (rc_out_undecodable_ > rc_out_undecodable_before_) {
    status.summary(DiagnosticStatus::ERROR, params_.rc_out_topic + ": " + decode_error_);
  } else if (new_problems > 0) {
    status.summary(DiagnosticStatus::WARN, describe(estimator_->lastRejection()));
  } else if (last_rc_out_verdict_ == Rejection::kDisarmed) {
    status.summary(DiagnosticStatus::OK, describe(estimator_->lastRejection()));
  } else {
    status.summary(DiagnosticStatus::OK, "ok");
  }
  outputs_before_ = now;
  rc_out_undecodable_before_ = rc_out_undecodable_;
}

void EstimatorNode::diagnoseDomain(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const Snapshot now = takeSnapshot();
  const std::uint64_t samples = now.counters.motor_samples - domain_before_.counters.motor_samples;
  const std::uint64_t outside =
      now.counters.motor_samples_outside_domain - domain_before_.counters.motor_samples_outside_domain;
  const double fraction = samples ? static_cast<double>(outside) / static_cast<double>(samples) : 0.0;
  const ModelDomain& d = estimator_->model().domain();
  status.add("fraction outside domain", fraction);
  status.add("samples outside domain (total)", now.counters.motor_samples_outside_domain);
  status.add("domain", std::to_string(d.pwm_min_us) + "-" + std::to_string(d.pwm_max_us) + " us, " +
                           std::to_string(d.voltage_min_v) + "-" + std::to_string(d.voltage_max_v) + " V");
  if (fraction > params_.domain_warn_fraction) {
    std::ostringstream message;
    message.precision(3);
    message << 100.0 * fraction << " % of motor samples outside the model's domain (" << outsideDomainName(d.outside)
            << "ed)";
    status.summary(DiagnosticStatus::WARN, message.str());
  } else {
    status.summary(DiagnosticStatus::OK, "within the measured domain");
  }
  domain_before_ = now;
}

void EstimatorNode::diagnosePayload(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const MassEstimate& p = estimator_->output().payload;
  status.add("state", payloadStateName(p.state));
  status.add("hovering", p.hovering);
  status.add("total mass (kg)", p.total_mass_kg);
  status.add("empty mass (kg)", p.empty_mass_kg);
  status.add("empty mass source", emptyMassSourceName(p.empty_mass_source));
  status.add("payload mass (kg)", p.payload_mass_kg);
  status.add("hover", estimator_->describeHover());
  status.summary(DiagnosticStatus::OK, payloadStateName(p.state));
}

}  // namespace propulsion_estimator
