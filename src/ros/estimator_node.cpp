#include "propulsion_estimator/ros/estimator_node.h"

#include <cmath>
#include <ctime>
#include <functional>
#include <sstream>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/onboard/tare_file.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"

namespace propulsion_estimator {
namespace {

using diagnostic_msgs::DiagnosticStatus;

// `read()` of the file `parameter` names, a refusal naming the parameter too: "/n/model: /x.yaml: ...".
template <typename Read>
auto readParameterFile(const ros::NodeHandle& private_nh, const std::string& parameter, Read read) {
  try {
    return read();
  } catch (const InputError& e) {
    throw ConfigError(private_nh.resolveName(parameter) + ": " + e.what());
  }
}

Vehicle loadVehicle(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh, const EstimatorNodeParams& params) {
  if (!params.urdf_file.empty()) {
    ROS_INFO_STREAM("vehicle from URDF file " << params.urdf_file);
    return readParameterFile(private_nh, "urdf_file", [&] { return loadVehicleUrdf(params.urdf_file); });
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

std::uint8_t diagnosticLevel(HealthLevel level) {
  switch (level) {
    case HealthLevel::kOk: return DiagnosticStatus::OK;
    case HealthLevel::kWarn: return DiagnosticStatus::WARN;
    case HealthLevel::kError: return DiagnosticStatus::ERROR;
  }
  return DiagnosticStatus::ERROR;
}

}  // namespace

void EstimatorNode::copy(const HealthStatus& health, diagnostic_updater::DiagnosticStatusWrapper* status) {
  for (const auto& [key, value] : health.values) status->add(key, value);
  status->summary(diagnosticLevel(health.level), health.message);
}

EstimatorNode::EstimatorNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : params_(readEstimatorNodeParams(private_nh)),
      pack_file_(params_.pack_file, params_.capability.cells.value_or(0)),
      diagnostics_(nh, private_nh),
      publish_limiter_(params_.publish_rate_hz) {
  PropulsionModel model = readParameterFile(private_nh, "model", [&] { return loadModelFile(params_.model); });
  identifyPack(params_.pack_id, true);
  model_fingerprint_ = modelFingerprint(model);
  Vehicle vehicle = loadVehicle(nh, private_nh, params_);
  session_ = std::make_unique<OnboardSession>(
      std::move(model), std::move(vehicle),
      OnboardConfig{params_.estimator, params_.capability, params_.esc_telemetry, params_.mass_view},
      params_.model);
  // The model now lives in the session: read its metadata there, not from the moved-from local.
  const Estimator& estimator = session_->estimator();
  const ModelMetadata& meta = estimator.model().metadata();
  const ModelDomain& domain = estimator.model().domain();
  ROS_INFO_STREAM("model " << params_.model << ": " << meta.esc << " + " << meta.motor << " + " << meta.propeller
                           << ", domain " << domain.pwm_min_us << "-" << domain.pwm_max_us << " us, "
                           << domain.voltage_min_v << "-" << domain.voltage_max_v
                           << " V, outside: " << outsideDomainName(domain.outside)
                           << "; outputs not modelled (published as NaN): " << unmodelledOutputs(estimator.model()));
  logMotorChecks();
  loadTare();
  const MassEstimate& payload = estimator.output().payload;
  ROS_INFO_STREAM("empty mass: " << (std::isnan(payload.empty_mass_kg) ? std::string("unknown until ~tare")
                                                                       : std::to_string(payload.empty_mass_kg) + " kg")
                                 << " (source: " << emptyMassSourceName(payload.empty_mass_source) << ")");

  const std::size_t motors = estimator.vehicle().rotors.size();
  motors_msg_.motors.resize(motors);
  for (std::size_t i = 0; i < motors; ++i) {
    motors_msg_.motors[i].channel = static_cast<std::uint8_t>(params_.estimator.motor_channels[i]);
  }
  rc_out_.channels.reserve(32);
  // The estimates' queues hold half a second at 1000 Hz (about 100 kB at most): on a loaded
  // companion computer a subscriber may not read for tens of milliseconds, and a shorter queue drops
  // messages (the soak rostest counts every answer). RCOut is handled as it is read (input_queue_);
  // its queue matters only for a message handed to ros::spin() (InlineCallbackQueue's fallback).
  constexpr std::uint32_t queue = 500;
  motors_pub_ = private_nh.advertise<MotorEstimates>("motors", queue);
  totals_pub_ = private_nh.advertise<PropulsionTotals>("totals", queue);
  payload_pub_ = private_nh.advertise<PayloadEstimate>("payload", queue);
  capability_pub_ = private_nh.advertise<Capability>("capability", 2);
  tare_srv_ = private_nh.advertiseService("tare", &EstimatorNode::onTare, this);
  detect_hover_srv_ = private_nh.advertiseService("detect_hover", &EstimatorNode::onDetectHover, this);
  reset_srv_ = private_nh.advertiseService("reset", &EstimatorNode::onReset, this);

  diagnostics_.setHardwareID(meta.esc + " / " + meta.motor + " / " + meta.propeller);
  // Each task judges the period since its own previous run.
  diagnostics_.add("Inputs", [this](diagnostic_updater::DiagnosticStatusWrapper& status) {
    const HealthSnapshot now = takeSnapshot();
    copy(judgeInputs(session_->estimator(), inputs_before_, now, params_.health), &status);
    inputs_before_ = now;
  });
  diagnostics_.add("Motor outputs", [this](diagnostic_updater::DiagnosticStatusWrapper& status) {
    const HealthSnapshot now = takeSnapshot();
    copy(judgeMotorOutputs(session_->estimator(), outputs_before_, now, params_.health), &status);
    outputs_before_ = now;
  });
  diagnostics_.add("Model domain", [this](diagnostic_updater::DiagnosticStatusWrapper& status) {
    const HealthSnapshot now = takeSnapshot();
    copy(judgeDomain(session_->estimator(), domain_before_, now, params_.health), &status);
    domain_before_ = now;
  });
  diagnostics_.add("Payload", [this](diagnostic_updater::DiagnosticStatusWrapper& status) {
    copy(session_->payloadHealth(ros::Time::now().toSec()), &status);
  });
  diagnostics_.add("Tare file", [this](diagnostic_updater::DiagnosticStatusWrapper& status) {
    status.add("tare_file", params_.tare_file);
    status.summary(tare_file_level_, tare_file_message_);
  });
  diagnostics_.add("Pack file",
                   [this](diagnostic_updater::DiagnosticStatusWrapper& status) { packFileStatus(&status); });
  diagnostics_.add("Effects", [this](diagnostic_updater::DiagnosticStatusWrapper& status) {
    const HealthSnapshot now = takeSnapshot();
    copy(judgeEffects(session_->estimator(), effects_before_, now, params_.health), &status);
    effects_before_ = now;
  });
  diagnostics_.add("Capability", [this](diagnostic_updater::DiagnosticStatusWrapper& status) {
    copy(judgeCapability(last_capability_.capability, last_capability_.motor_health, params_.capability), &status);
  });
  inputs_before_ = outputs_before_ = domain_before_ = effects_before_ = takeSnapshot();
  // One tick per diagnostic_period, not a polling timer: every tick wakes two of roscpp's threads.
  diagnostics_timer_ = nh.createTimer(ros::Duration(params_.diagnostic_period_s), [this](const ros::TimerEvent&) {
    const std::lock_guard<std::mutex> lock(state_);
    diagnostics_.force_update();
  });
  capability_timer_ = nh.createTimer(ros::Duration(1.0 / params_.capability.rate_hz), [this](const ros::TimerEvent&) {
    const std::lock_guard<std::mutex> lock(state_);
    publishCapability();
  });

  // Subscribed last: from here on, callbacks run in roscpp's network thread (input_queue_), before
  // ros::spin() is reached.
  ros::NodeHandle input_nh(nh);
  input_nh.setCallbackQueue(&input_queue_);
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  subscribeEffectSignals(input_nh, private_nh, hints);
  setUpEscTelemetry(input_nh, hints);
  rc_out_sub_ = input_nh.subscribe(params_.rc_out_topic, queue, &EstimatorNode::onRcOut, this, hints);
  battery_sub_ = input_nh.subscribe(params_.battery_topic, 5, &EstimatorNode::onBattery, this, hints);
  if (!params_.imu_topic.empty()) {
    imu_sub_ = input_nh.subscribe(params_.imu_topic, 20, &EstimatorNode::onImu, this, hints);
  }
  if (!params_.velocity_topic.empty()) {
    velocity_sub_ = input_nh.subscribe(params_.velocity_topic, 20, &EstimatorNode::onVelocity, this, hints);
  }
}

void EstimatorNode::logMotorChecks() const {
  const std::optional<MotorReference>& reference = session_->estimator().model().motorReference();
  ROS_INFO_STREAM("motor health: " << (reference ? "each motor against the model's reference of " +
                                                       std::to_string(reference->flights) + " healthy flights"
                                                 : std::string("against the ideal balance, beyond the spread healthy "
                                                               "vehicles show (no motor_reference in the model)")));
  if (reference && !reference->esc_rpm_deviation.empty()) {
    ROS_INFO_STREAM("live ESC check: each motor against the model's reference of " << reference->flights
                                                                                   << " healthy flights");
  }
}

void EstimatorNode::loadTare() {
  if (params_.tare_file.empty()) {
    setTareFileStatus(DiagnosticStatus::OK, "none: tare_file is empty, ~tare is not persisted");
    return;
  }
  for (const std::string& stale : removeStaleTareTemporaries(params_.tare_file)) {
    ROS_WARN_STREAM("tare file: removed " << stale << ", left by a ~tare that was interrupted");
  }
  // A tare file that cannot be read must not keep the node (required in the launch) from starting.
  const TareAtStart start = loadTareAtStart(params_.tare_file, static_cast<long long>(std::time(nullptr)));
  if (!start.refusal.empty()) {
    setTareFileStatus(DiagnosticStatus::WARN, start.refusal);
    return;
  }
  const std::optional<TareRecord>& tare = start.record;
  if (!tare) {
    setTareFileStatus(DiagnosticStatus::OK, params_.tare_file + ": none yet");
  } else if (tare->model_fingerprint == model_fingerprint_) {
    session_->setEmptyMass(tare->empty_mass_kg, EmptyMassSource::kTareFile);
    std::ostringstream message;
    message << params_.tare_file << ": empty mass " << tare->empty_mass_kg << " kg";
    setTareFileStatus(DiagnosticStatus::OK, message.str());
  } else {
    setTareFileStatus(DiagnosticStatus::WARN, params_.tare_file + ": ignored: it was taken with another model (" +
                                                  tare->model + ", fingerprint " + tare->model_fingerprint + ") than " +
                                                  params_.model + " (fingerprint " + model_fingerprint_ + ")");
  }
}

void EstimatorNode::identifyPack(const std::string& pack_id, bool before_start) {
  if (!pack_file_.enabled() || pack_id.empty()) return;
  const std::optional<PackRecord> record = pack_file_.identify(pack_id, static_cast<long long>(std::time(nullptr)));
  logPackFile(pack_file_.note(), pack_file_.refused() || !pack_file_.active());
  if (!record) return;
  if (before_start) {
    params_.capability.pack = record;
  } else if (!session_->usePack(*record)) {
    ROS_WARN_STREAM("pack file: pack \"" << pack_id << "\" identified after the first battery reading: its record "
                                          "is not used on this flight");
  }
}

void EstimatorNode::logPackFile(const std::string& line, bool warn) {
  if (warn) {
    ROS_WARN_STREAM("pack file: " << line);
  } else {
    ROS_INFO_STREAM("pack file: " << line);
  }
}

void EstimatorNode::packFileStatus(diagnostic_updater::DiagnosticStatusWrapper* status) const {
  status->add("pack_file", params_.pack_file);
  if (!pack_file_.enabled()) {
    status->summary(DiagnosticStatus::OK, "none: capability/battery/pack_file is empty, no pack is learned");
    return;
  }
  if (!pack_file_.identified()) {
    status->summary(DiagnosticStatus::WARN, "no pack identity yet: capability/battery/pack_id is empty and no "
                                            "BatteryState.serial_number has come");
    return;
  }
  std::string note = pack_file_.note();
  // A replay or a power-off soon after the landing learns nothing: said while the rest lasts.
  const double rest_left_s = session_->capabilityEstimator().packRestLeftS();
  if (pack_file_.active() && !std::isnan(rest_left_s)) {
    note += formatPrintf("; landed: this flight is learned once the pack has rested %.0f s more", rest_left_s);
  }
  status->summary(pack_file_.active() && !pack_file_.refused() ? DiagnosticStatus::OK : DiagnosticStatus::WARN, note);
}

void EstimatorNode::learnPack() {
  if (!pack_file_.active() || !session_->packFlightFinished()) return;
  const std::string line = pack_file_.save(session_->learnPack(pack_file_.previous()));
  logPackFile(line, pack_file_.refused());
}

void EstimatorNode::setTareFileStatus(std::uint8_t level, const std::string& message) {
  tare_file_level_ = level;
  tare_file_message_ = message;
  if (level == DiagnosticStatus::OK) {
    ROS_INFO_STREAM("tare file: " << message);
  } else {
    ROS_WARN_STREAM("tare file: " << message);
  }
}

void EstimatorNode::subscribeEffectSignals(ros::NodeHandle& input_nh, const ros::NodeHandle& private_nh,
                                           const ros::TransportHints& hints) {
  const effects::ModelEffects& fx = session_->estimator().model().effects();
  // A needed topic set to "" would skip its correction for the whole flight: refused at start.
  const auto require = [this, &private_nh](effects::Kind kind, const std::string& parameter, const std::string& topic) {
    if (topic.empty()) {
      throw ConfigError(private_nh.resolveName(parameter) + ": empty, but the model's " + effects::kindName(kind) +
                        " effect (" + params_.model + ") reads it");
    }
  };
  for (effects::Kind kind : effects::kAllKinds) {
    if (!fx.has(kind)) continue;
    const effects::Signal signal = effects::requiredSignal(kind);
    for (input::Scalar scalar : input::kAllScalars) {
      if (effects::preparedFrom(signal, scalar)) {
        require(kind, input::topicParameter(scalar), params_.input_topics[input::index(scalar)]);
      }
    }
    if (signal == effects::Signal::kVerticalSpeed || signal == effects::Signal::kHorizontalSpeed ||
        signal == effects::Signal::kAxialSpeed) {
      require(kind, "velocity_topic", params_.velocity_topic);
    }
  }
  for (input::Scalar scalar : input::kAllScalars) {
    const std::string& topic = params_.input_topics[input::index(scalar)];
    if (session_->readsInput(scalar) && !topic.empty()) {
      input_subs_[input::index(scalar)] = subscribeInput(input_nh, scalar, topic, hints);
    }
  }
  if (fx.empty()) {
    ROS_INFO_STREAM("effects: none (" << params_.model << " has no effects: section)");
    return;
  }
  for (effects::Kind kind : effects::kAllKinds) {
    if (!fx.has(kind)) continue;
    const effects::Signal signal = effects::requiredSignal(kind);
    ROS_INFO_STREAM("effect applied: " << effects::kindName(kind) << " (" << effects::describeParameters(kind, fx)
                                       << (signal == effects::Signal::kNone
                                               ? std::string(")")
                                               : "; reads the " + signalSource(signal, params_.health) + ")"));
  }
}

namespace {

constexpr std::uint32_t kInputQueue = 20;

// Subscribes to `topic`, handing each message's field (`field` reads it) to `take`.
template <typename Message, typename Field>
ros::Subscriber subscribeScalar(ros::NodeHandle& input_nh, const std::string& topic, const ros::TransportHints& hints,
                                Field field, std::function<void(double)> take) {
  return input_nh.subscribe<Message>(
      topic, kInputQueue,
      boost::function<void(const typename Message::ConstPtr&)>(
          [field, take](const typename Message::ConstPtr& message) { take(field(*message)); }),
      ros::VoidConstPtr(), hints);
}

}  // namespace

ros::Subscriber EstimatorNode::subscribeInput(ros::NodeHandle& input_nh, input::Scalar scalar,
                                              const std::string& topic, const ros::TransportHints& hints) {
  const auto take = [this, scalar](double value) { onInput(scalar, value); };
  switch (input::spec(scalar).message) {
    case input::Message::kFluidPressure:
      return subscribeScalar<sensor_msgs::FluidPressure>(
          input_nh, topic, hints, [](const sensor_msgs::FluidPressure& m) { return m.fluid_pressure; }, take);
    case input::Message::kTemperature:
      return subscribeScalar<sensor_msgs::Temperature>(
          input_nh, topic, hints, [](const sensor_msgs::Temperature& m) { return m.temperature; }, take);
    case input::Message::kRange:
      return input_nh.subscribe(topic, kInputQueue, &EstimatorNode::onRange, this, hints);
  }
  return {};
}

HealthSnapshot EstimatorNode::takeSnapshot() const {
  return HealthSnapshot{ros::Time::now().toSec(), inputs_, session_->estimator().counters()};
}

void EstimatorNode::onRcOut(const topic_tools::ShapeShifter::ConstPtr& message) {
  const std::lock_guard<std::mutex> lock(state_);
  ++inputs_.received[static_cast<int>(NodeInput::kRcOut)];
  if (!decoder_.decode(*message, &rc_out_, &inputs_.last_decoding_error)) {
    ++inputs_.rc_out_undecodable;
    ROS_ERROR_STREAM_THROTTLE(5.0, params_.rc_out_topic << ": " << inputs_.last_decoding_error);
    return;
  }
  inputs_.last_rc_out_verdict = session_->addMotorOutputs(rc_out_.header.stamp.toSec(), ros::Time::now().toSec(),
                                                          rc_out_.channels.data(), rc_out_.channels.size());
  if (inputs_.last_rc_out_verdict != Rejection::kNone) {
    logRejection(inputs_.last_rc_out_verdict);
    return;
  }
  // Estimated and averaged always; published at most at publish_rate_hz (on the stamps, so that a
  // replayed bag publishes as the flight did).
  if (publish_limiter_.admit(session_->estimator().output().stamp_s)) publish();
}

void EstimatorNode::onBattery(const sensor_msgs::BatteryState::ConstPtr& message) {
  const std::lock_guard<std::mutex> lock(state_);
  ++inputs_.received[static_cast<int>(NodeInput::kBattery)];
  if (pack_file_.enabled() && !pack_file_.identified() && !message->serial_number.empty()) {
    identifyPack(message->serial_number, false);
  }
  logRejection(session_->addBattery(ros::Time::now().toSec(), message->voltage, message->current, message->percentage,
                                    message->temperature));
  learnPack();
  const double applied_ohm = session_->supplyAppliedOhm();
  if (!supply_logged_ && !std::isnan(applied_ohm)) {
    ROS_INFO_STREAM("supply_resistance effect applied from ESC telemetry: " << applied_ohm << " ohm");
    supply_logged_ = true;
  }
}

void EstimatorNode::onImu(const sensor_msgs::Imu::ConstPtr& message) {
  const std::lock_guard<std::mutex> lock(state_);
  ++inputs_.received[static_cast<int>(NodeInput::kImu)];
  // REP-145: a covariance of -1 says the orientation is not provided.
  if (message->orientation_covariance[0] == -1.0) {
    ++inputs_.imu_without_orientation;
    ROS_WARN_STREAM_THROTTLE(30.0, params_.imu_topic << " carries no orientation: tilt and acceleration not compensated");
    return;
  }
  const auto& q = message->orientation;
  const auto& a = message->linear_acceleration;
  logRejection(session_->addImu(ros::Time::now().toSec(), Eigen::Quaterniond(q.w, q.x, q.y, q.z),
                                  Eigen::Vector3d(a.x, a.y, a.z)));
}

void EstimatorNode::onVelocity(const geometry_msgs::TwistStamped::ConstPtr& message) {
  const std::lock_guard<std::mutex> lock(state_);
  ++inputs_.received[static_cast<int>(NodeInput::kVelocity)];
  const double now_s = ros::Time::now().toSec();
  logRejection(session_->addVerticalSpeed(now_s, message->twist.linear.z));
  logRejection(session_->addHorizontalVelocity(now_s, message->twist.linear.x, message->twist.linear.y));
}

void EstimatorNode::onInput(input::Scalar scalar, double value) {
  const std::lock_guard<std::mutex> lock(state_);
  logRejection(session_->addInput(scalar, ros::Time::now().toSec(), value));
}

void EstimatorNode::onRange(const sensor_msgs::Range::ConstPtr& message) {
  const std::lock_guard<std::mutex> lock(state_);
  logRejection(session_->addRange(ros::Time::now().toSec(), message->range, message->min_range,
                                    message->max_range));
}

void EstimatorNode::logRejection(Rejection rejection) {
  if (rejection == Rejection::kNone) return;
  if (rejection == Rejection::kDisarmed) {
    ROS_INFO_STREAM_THROTTLE(30.0, describe(session_->estimator().lastRejection()));
  } else {
    ROS_WARN_STREAM_THROTTLE(5.0, describe(session_->estimator().lastRejection()));
  }
}

void EstimatorNode::publish() {
  const EstimatorOutput& out = session_->estimator().output();
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
  fillMeasured(ros::Time::now().toSec());
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

void EstimatorNode::publishCapability() {
  last_capability_ = session_->capability(ros::Time::now().toSec());
  const CapabilityReport& c = last_capability_.capability;
  const MotorHealthVerdict& h = last_capability_.motor_health;
  Capability msg;
  msg.header.stamp = ros::Time::now();
  msg.hover_mass_kg = c.hover_mass_kg;
  msg.hover_basis = c.hover_basis;
  msg.voltage_v = c.voltage_v;
  msg.pwm_max_us = c.pwm_max_us;
  msg.min_thrust_to_weight = params_.capability.min_thrust_to_weight;
  msg.max_thrust_n = c.max_thrust_n;
  msg.thrust_to_weight = c.thrust_to_weight;
  msg.max_additional_payload_kg = c.max_additional_payload_kg;
  msg.full_throttle_voltage_v = c.full_throttle_voltage_v;
  msg.full_throttle_current_a = c.full_throttle_current_a;
  msg.cutoff_voltage_v = c.cutoff_voltage_v;
  msg.max_thrust_at_cutoff_n = c.max_thrust_at_cutoff_n;
  msg.thrust_to_weight_at_cutoff = c.thrust_to_weight_at_cutoff;
  msg.max_additional_payload_at_cutoff_kg = c.max_additional_payload_at_cutoff_kg;
  msg.payload_note = c.payload_note;
  msg.hover_pwm_us = c.hover_pwm_us;
  msg.hover_current_a = c.hover_current_a;
  msg.state_of_charge = c.state_of_charge;
  msg.state_of_charge_std = c.state_of_charge_std;
  msg.internal_resistance_ohm = c.internal_resistance_ohm;
  msg.internal_resistance_std_ohm = c.internal_resistance_std_ohm;
  msg.open_circuit_voltage_v = c.open_circuit_voltage_v;
  msg.charge_basis = c.charge_basis;
  msg.remaining_ah = c.remaining_ah;
  msg.hover_endurance_s = c.hover_endurance_s;
  msg.hover_endurance_std_s = c.hover_endurance_std_s;
  msg.unmodelled_current_a = c.unmodelled_current_a;
  msg.hover_endurance_low_s = c.hover_endurance_low_s;
  msg.hover_endurance_high_s = c.hover_endurance_high_s;
  msg.endurance_basis = c.endurance_basis;
  msg.reserve_s = params_.capability.reserve_s;
  msg.motor_health_judged = h.judged;
  msg.motor_health_note = h.unavailable;
  msg.yaw_imbalance = h.yaw_imbalance;
  msg.yaw_imbalance_std = h.yaw_imbalance_std;
  for (const MotorBalanceGap& motor : h.motors) {
    msg.motor_channels.push_back(static_cast<std::uint8_t>(motor.channel));
    msg.motor_thrust_gap.push_back(motor.thrust_gap);
    msg.motor_thrust_gap_std.push_back(motor.thrust_gap_std);
  }
  msg.flagged_channel = static_cast<std::uint8_t>(h.flagged_channel);
  msg.cg_offset_x_m = h.cg_offset_x_m;
  msg.cg_offset_y_m = h.cg_offset_y_m;
  fillModelCheck(last_capability_, &msg);
  msg.payload_over_limit = c.payload_over_limit;
  msg.endurance_below_reserve = c.endurance_below_reserve;
  capability_pub_.publish(msg);
}

bool EstimatorNode::onTare(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  TareResult tare;
  {
    const std::lock_guard<std::mutex> lock(state_);
    tare = session_->tare(ros::Time::now().toSec());
  }
  // The file is written (fsync) without the lock: the network thread goes on estimating meanwhile.
  response.success = tare.ok;
  response.message = tare.message;
  if (tare.ok && !params_.tare_file.empty()) {
    try {
      saveTareFile(params_.tare_file, TareRecord{tare.empty_mass_kg, params_.model, model_fingerprint_});
      response.message += ", saved to " + params_.tare_file;
      setTareFileStatus(DiagnosticStatus::OK, params_.tare_file + ": " + tare.message + " (~tare)");
    } catch (const InputError& e) {
      response.success = false;
      response.message += std::string(", applies to this run only: ") + e.what();
      setTareFileStatus(DiagnosticStatus::WARN, std::string("~tare not persisted: ") + e.what());
    }
  }
  ROS_INFO_STREAM("~tare: " << response.message);
  return true;
}

bool EstimatorNode::onDetectHover(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  const std::lock_guard<std::mutex> lock(state_);
  std::tie(response.success, response.message) = session_->detectHover(ros::Time::now().toSec());
  return true;
}

bool EstimatorNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  std::unique_lock<std::mutex> lock(state_);
  session_->reset();
  const MassEstimate p = session_->estimator().output().payload;
  lock.unlock();
  std::ostringstream message;
  message << "windows and tare cleared; empty mass now "
          << (std::isnan(p.empty_mass_kg) ? std::string("unknown") : std::to_string(p.empty_mass_kg) + " kg")
          << " (source: " << emptyMassSourceName(p.empty_mass_source) << ")";
  response.success = true;
  if (!params_.tare_file.empty()) {
    try {
      const bool removed = removeTareFile(params_.tare_file);
      setTareFileStatus(DiagnosticStatus::OK,
                        params_.tare_file + (removed ? ": removed by ~reset" : ": none (~reset had none to remove)"));
    } catch (const InputError& e) {
      response.success = false;
      message << "; but " << e.what() << ", and the next start reads it again";
      setTareFileStatus(DiagnosticStatus::WARN, std::string("~reset: ") + e.what());
    }
  }
  response.message = message.str();
  ROS_INFO_STREAM("~reset: " << response.message);
  return true;
}

}  // namespace propulsion_estimator
