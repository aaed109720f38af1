#include "propulsion_estimator/estimation/estimator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/estimation/tare_verdict.h"
#include "propulsion_estimator/model/effect_signals.h"

namespace propulsion_estimator {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// What the effects' signals can be; beyond, the reading is in another unit (mA, hPa, K) or broken.
// The scalar inputs' ranges are in their entries (input_signal.h).
constexpr double kMaxBatteryCurrentA = 1000.0;

}  // namespace

const char* rejectionName(Rejection rejection) {
  static const char* const kNames[kRejectionCount] = {
      "none",           "bad_voltage",  "bad_imu",         "bad_velocity", "no_battery",    "stale_battery",
      "disarmed",       "too_few_channels", "time_backwards", "stamp_ahead", "duplicate", "outside_domain",
      "non_finite_estimate",
      "bad_battery_current", "bad_input"};
  return kNames[static_cast<int>(rejection)];
}

std::string badInputName(input::Scalar scalar) { return std::string("bad_") + input::spec(scalar).name; }

const char* verticalSpeedSourceName(VerticalSpeedSource source) {
  switch (source) {
    case VerticalSpeedSource::kNone: return "none";
    case VerticalSpeedSource::kVelocity: return "velocity";
    case VerticalSpeedSource::kBarometer: return "barometer";
  }
  return "?";
}

std::string describe(const RejectionDetail& d) {
  std::ostringstream out;
  switch (d.reason) {
    case Rejection::kNone: return "none";
    case Rejection::kBadVoltage: out << "battery voltage " << d.value << " V refused (must be finite and positive)"; break;
    case Rejection::kBadImu: out << "IMU message refused (non-finite or non-unit orientation, or non-finite acceleration)"; break;
    case Rejection::kBadVelocity: out << "vertical speed " << d.value << " m/s refused (not finite)"; break;
    case Rejection::kNoBattery: out << "motor outputs ignored: no valid battery voltage received yet"; break;
    case Rejection::kStaleBattery:
      out << "motor outputs ignored: newest battery voltage is " << d.value << " s old (limit " << d.limit << " s)";
      break;
    case Rejection::kDisarmed:
      out << "motor outputs ignored: channel " << d.channel << " at " << d.value << " us, at or below disarmed_pwm_max_us "
          << d.limit << " (disarmed or stopped)";
      break;
    case Rejection::kTooFewChannels:
      out << "motor outputs ignored: RCOut has " << d.value << " channels, motor channel " << d.limit << " is configured";
      break;
    case Rejection::kTimeBackwards:
      out << "motor outputs ignored: stamp went back by " << d.value << " s";
      break;
    case Rejection::kStampAhead:
      out << "motor outputs ignored: stamped " << d.value << " s ahead of the receiving clock (limit max_stamp_ahead_s "
          << d.limit << " s)";
      break;
    case Rejection::kDuplicate:
      out << "motor outputs ignored: stamp " << d.value << " s is the previous accepted message's (a duplicate)";
      break;
    case Rejection::kOutsideDomain:
      out << "motor outputs ignored: channel " << d.channel << " at " << d.value
          << " us (or the voltage) outside the model's domain, which says reject";
      break;
    case Rejection::kNonFiniteEstimate:
      out << "motor outputs ignored: the model gives a non-finite value for channel " << d.channel << " at "
          << d.value << " us and " << d.limit << " V (a pole of a rational surface when extrapolating?)";
      break;
    case Rejection::kBadBatteryCurrent:
      out << "battery current " << d.value << " A refused (must be finite, at most " << kMaxBatteryCurrentA
          << " A either way)";
      break;
    case Rejection::kBadInput: {
      const input::ScalarSpec& input = input::spec(d.input);
      out << input.description << " " << d.value << " " << input.unit << " refused (";
      if (input.message == input::Message::kRange) {
        out << "NaN, or outside the sensor's min_range..max_range " << d.limit << ".." << d.limit_high
            << " m, which sensor_msgs/Range says to discard)";
      } else {
        out << "outside " << d.limit << ".." << d.limit_high << " " << input.unit << ")";
      }
      break;
    }
  }
  return out.str();
}

Estimator::Estimator(PropulsionModel model, Vehicle vehicle, EstimatorConfig config)
    : model_(std::move(model)),
      vehicle_(std::move(vehicle)),
      // Validated before the windows below are sized from it.
      config_((config.validate(vehicle_.rotors.size()), std::move(config))),
      hover_(config_.hover),
      payload_(config_.payload),
      accel_filter_(config_.accel_filter_s, config_.accel_bias_filter_s),
      has_current_(model_.output(Output::kCurrent).source != OutputSource::kNone),
      has_power_(model_.output(Output::kPower).source != OutputSource::kNone),
      has_efficiency_(model_.output(Output::kEfficiency).source != OutputSource::kNone) {
  if (config_.empty_mass_kg) {
    configured_empty_mass_kg_ = config_.empty_mass_kg;
    configured_source_ = EmptyMassSource::kParameter;
  } else if (vehicle_.empty_mass) {
    configured_empty_mass_kg_ = vehicle_.empty_mass->mass_kg;
    configured_source_ = EmptyMassSource::kUrdf;
  }
  if (configured_empty_mass_kg_) payload_.setEmptyMass(*configured_empty_mass_kg_, configured_source_);
  output_.motors.resize(vehicle_.rotors.size());
  scratch_.resize(vehicle_.rotors.size());
  for (std::size_t i = 0; i < output_.motors.size(); ++i) output_.motors[i].channel = config_.motor_channels[i];
  output_.payload = payload_.estimate();
}

Rejection Estimator::reject(Rejection reason, int channel, double value, double limit, double limit_high) {
  ++counters_.rejected[static_cast<int>(reason)];
  last_rejection_ = RejectionDetail{reason, channel, value, limit, limit_high};
  return reason;
}

double Estimator::Reading::at(double now_s, double timeout_s) const {
  return have && now_s - receipt_s <= timeout_s ? value : kNaN;
}

void Estimator::checkClock(double receipt_s) {
  if (receipt_s < last_receipt_s_ - config_.clock_jump_reset_s) {
    // The clock restarted (a bag played again): everything received belongs to another timeline.
    clearWindows();
    accel_filter_.clear();
    barometric_speed_.clear();
    have_voltage_ = have_imu_ = have_velocity_ = have_stamp_ = have_accepted_ = false;
    battery_current_a_.have = false;
    for (Reading& reading : inputs_) reading.have = false;
    ++counters_.clock_resets;
  }
  last_receipt_s_ = receipt_s;
  expireHover(receipt_s);
}

void Estimator::expireHover(double now_s) {
  if (!have_accepted_ || now_s - last_accepted_receipt_s_ <= config_.hover.window_s) return;
  if (hover_.verdict().samples == 0) return;  // nothing to expire (expired, landed or reset already)
  hover_.expire();
  payload_.endHover();
  output_.hover = hover_.verdict();
  output_.payload = payload_.estimate();
}

Rejection Estimator::addBattery(double receipt_s, double voltage_v) {
  checkClock(receipt_s);
  if (!std::isfinite(voltage_v) || voltage_v <= 0.0) return reject(Rejection::kBadVoltage, 0, voltage_v);
  voltage_v_ = voltage_v;
  voltage_receipt_s_ = receipt_s;
  have_voltage_ = true;
  return Rejection::kNone;
}

Rejection Estimator::addImu(double receipt_s, const Eigen::Quaterniond& orientation,
                            const Eigen::Vector3d& specific_force) {
  checkClock(receipt_s);
  if (!orientation.coeffs().allFinite() || std::fabs(orientation.norm() - 1.0) > 0.01 || !specific_force.allFinite()) {
    return reject(Rejection::kBadImu);
  }
  body_to_world_ = orientation.normalized().toRotationMatrix();
  const double vertical_specific_force = body_to_world_.row(2).dot(specific_force);
  accel_filter_.add(receipt_s, vertical_specific_force - kStandardGravity);
  imu_receipt_s_ = receipt_s;
  have_imu_ = true;
  return Rejection::kNone;
}

Rejection Estimator::addVerticalSpeed(double receipt_s, double vertical_speed_m_s) {
  checkClock(receipt_s);
  if (!std::isfinite(vertical_speed_m_s)) return reject(Rejection::kBadVelocity, 0, vertical_speed_m_s);
  vertical_speed_m_s_ = vertical_speed_m_s;
  velocity_receipt_s_ = receipt_s;
  have_velocity_ = true;
  return Rejection::kNone;
}

Rejection Estimator::addHorizontalVelocity(double receipt_s, double east_m_s, double north_m_s) {
  checkClock(receipt_s);
  if (!std::isfinite(east_m_s)) return reject(Rejection::kBadVelocity, 0, east_m_s);
  if (!std::isfinite(north_m_s)) return reject(Rejection::kBadVelocity, 0, north_m_s);
  velocity_east_m_s_ = east_m_s;
  velocity_north_m_s_ = north_m_s;
  horizontal_receipt_s_ = receipt_s;
  return Rejection::kNone;
}

Rejection Estimator::addBatteryCurrent(double receipt_s, double current_a) {
  checkClock(receipt_s);
  if (std::isnan(current_a)) return Rejection::kNone;
  if (!(std::fabs(current_a) <= kMaxBatteryCurrentA)) return reject(Rejection::kBadBatteryCurrent, 0, current_a);
  battery_current_a_.set(receipt_s, current_a);
  return Rejection::kNone;
}

Rejection Estimator::rejectInput(input::Scalar scalar, double value, double limit, double limit_high) {
  ++counters_.rejected_inputs[input::index(scalar)];
  reject(Rejection::kBadInput, 0, value, limit, limit_high);
  last_rejection_.input = scalar;
  return Rejection::kBadInput;
}

Rejection Estimator::addInput(input::Scalar scalar, double receipt_s, double value) {
  checkClock(receipt_s);
  const input::ScalarSpec& spec = input::spec(scalar);
  if (!(value >= spec.min && value <= spec.max)) return rejectInput(scalar, value, spec.min, spec.max);
  inputs_[input::index(scalar)].set(receipt_s, value);
  if (scalar == input::Scalar::kStaticPressure) barometric_speed_.add(receipt_s, value);
  return Rejection::kNone;
}

Rejection Estimator::addRange(double receipt_s, double range_m, double min_range_m, double max_range_m) {
  checkClock(receipt_s);
  const input::Scalar range = input::Scalar::kRangefinder;
  double usable = range_m;
  if (!(min_range_m >= 0.0 && min_range_m < max_range_m && std::isfinite(max_range_m)) || std::isnan(range_m)) {
    return rejectInput(range, range_m, min_range_m, max_range_m);
  }
  if (range_m == -kInf) {
    usable = min_range_m;
  } else if (range_m != kInf && !(range_m >= min_range_m && range_m <= max_range_m)) {
    return rejectInput(range, range_m, min_range_m, max_range_m);
  }
  inputs_[input::index(range)].set(receipt_s, usable);
  return Rejection::kNone;
}

effects::Signals Estimator::effectSignals(double now_s) const {
  // The readings in force; their preparation is the diagnosis' too (effect_signals.h).
  effects::RawSignals raw;
  raw.battery_current_a = battery_current_a_.at(now_s, config_.battery_timeout_s);
  for (input::Scalar scalar : input::kAllScalars) {
    raw.input(scalar) = inputs_[input::index(scalar)].at(now_s, config_.inputTimeoutS(scalar));
  }
  raw.body_z_up = imuFresh(now_s) ? body_to_world_(2, 2) : 1.0;
  raw.vertical_speed_m_s = velocityFresh(now_s) ? vertical_speed_m_s_ : kNaN;
  if (now_s - horizontal_receipt_s_ <= config_.velocity_timeout_s) {
    raw.velocity_east_m_s = velocity_east_m_s_;
    raw.velocity_north_m_s = velocity_north_m_s_;
  }
  if (imuFresh(now_s)) {
    raw.body_z_east = body_to_world_(0, 2);
    raw.body_z_north = body_to_world_(1, 2);
  }
  return effects::prepareSignals(raw);
}

bool Estimator::imuFresh(double now_s) const {
  return have_imu_ && now_s - imu_receipt_s_ <= config_.imu_timeout_s;
}

bool Estimator::velocityFresh(double now_s) const {
  return have_velocity_ && now_s - velocity_receipt_s_ <= config_.velocity_timeout_s;
}

double Estimator::batteryAge(double now_s) const {
  return have_voltage_ ? now_s - voltage_receipt_s_ : std::numeric_limits<double>::infinity();
}

Rejection Estimator::addMotorOutputs(double stamp_s, double receipt_s, const std::uint16_t* channels,
                                     std::size_t count) {
  checkClock(receipt_s);
  Rejection rejection = checkBatteryAndChannels(receipt_s, channels, count);
  if (rejection == Rejection::kNone) rejection = checkStamp(receipt_s, &stamp_s);
  effects::KindMask skipped = 0;
  if (rejection == Rejection::kNone) rejection = evaluateMotors(receipt_s, channels, &skipped);
  if (rejection != Rejection::kNone) return rejection;

  const bool imu_fresh = imuFresh(receipt_s);
  const double vertical_accel = imu_fresh ? accel_filter_.value() : kNaN;
  const Totals totals = sumMotors(channels, imu_fresh, vertical_accel);
  VerticalSpeedSource speed_source = VerticalSpeedSource::kNone;
  const HoverSample sample = hoverSample(totals, receipt_s, imu_fresh, vertical_accel, &speed_source);
  output_.hover = hover_.add(stamp_s, sample);
  output_.payload = payload_.add(stamp_s, totals.mass_kg, output_.hover.hovering);
  output_.vertical_speed_source = speed_source;
  output_.totals = totals;
  output_.stamp_s = stamp_s;
  output_.effects_skipped = skipped;
  countAccepted(stamp_s, receipt_s, totals, skipped);
  return Rejection::kNone;
}

Rejection Estimator::checkBatteryAndChannels(double receipt_s, const std::uint16_t* channels, std::size_t count) {
  if (!have_voltage_) return reject(Rejection::kNoBattery);
  const double battery_age = receipt_s - voltage_receipt_s_;
  if (battery_age > config_.battery_timeout_s) {
    return reject(Rejection::kStaleBattery, 0, battery_age, config_.battery_timeout_s);
  }
  for (int channel : config_.motor_channels) {
    if (static_cast<std::size_t>(channel) > count) {
      return reject(Rejection::kTooFewChannels, 0, static_cast<double>(count), channel);
    }
  }
  for (int channel : config_.motor_channels) {
    const double pwm = channels[channel - 1];
    if (pwm <= config_.disarmed_pwm_max_us) {
      // On the ground between flights: the next hover may carry another payload.
      clearWindows();
      return reject(Rejection::kDisarmed, channel, pwm, config_.disarmed_pwm_max_us);
    }
  }
  return Rejection::kNone;
}

Rejection Estimator::checkStamp(double receipt_s, double* stamp_s) {
  if (*stamp_s == 0.0) {
    *stamp_s = receipt_s;  // an unstamped message is taken as stamped on arrival
  } else {
    // Accepted, a stamp far ahead would make every message of the next second go back in time.
    if (*stamp_s - receipt_s > config_.max_stamp_ahead_s) {
      return reject(Rejection::kStampAhead, 0, *stamp_s - receipt_s, config_.max_stamp_ahead_s);
    }
    // The same message twice (a relay, a bag recorded from two sources) would count twice in the
    // windows. Unstamped ones are exempt: two can arrive within one tick of a simulated clock.
    if (have_stamp_ && *stamp_s == last_stamp_s_) return reject(Rejection::kDuplicate, 0, *stamp_s);
  }
  if (have_stamp_ && *stamp_s < last_stamp_s_) {
    // A message out of order is refused; stamps that restart (an autopilot reboot, a time-sync
    // reset, a bag looped without --clock) would otherwise refuse everything that follows.
    if (last_stamp_s_ - *stamp_s <= config_.clock_jump_reset_s) {
      return reject(Rejection::kTimeBackwards, 0, last_stamp_s_ - *stamp_s);
    }
    clearWindows();
    ++counters_.clock_resets;
  }
  return Rejection::kNone;
}

Rejection Estimator::evaluateMotors(double receipt_s, const std::uint16_t* channels, effects::KindMask* skipped) {
  // Every motor is evaluated before anything is committed, so that a refusal leaves the
  // estimates as they were. The surfaces are evaluated at the inputs the ESCs really see.
  const effects::ModelEffects& model_effects = model_.effects();
  const effects::Signals signals = effectSignals(receipt_s);
  for (std::size_t i = 0; i < scratch_.size(); ++i) {
    const int channel = config_.motor_channels[i];
    const effects::Inputs in =
        effects::correctInputs(model_effects, channels[channel - 1], voltage_v_, signals, skipped);
    if (!model_.evaluate(in.pwm_us, in.voltage_v, &scratch_[i])) {
      return reject(Rejection::kOutsideDomain, channel, in.pwm_us);
    }
    OperatingPoint& p = scratch_[i];
    // Floored as the surfaces' thrust is: a linear law (climb inflow) pushed far past its range.
    // Per rotor: the air's law depends on the rotor's load.
    const double thrust_factor = std::max(0.0, effects::thrustFactor(model_effects, signals, p.thrust_n, skipped));
    // Efficiency is thrust over power: it follows the thrust, the power stays the surfaces'.
    p.thrust_n *= thrust_factor;
    p.efficiency_n_per_w *= thrust_factor;
    // An output the model lacks (`none`: a thrust-only stand) is NaN by design, not a fault.
    if (!std::isfinite(p.thrust_n) || (has_current_ && !std::isfinite(p.current_a)) ||
        (has_power_ && !std::isfinite(p.power_w)) || (has_efficiency_ && !std::isfinite(p.efficiency_n_per_w))) {
      return reject(Rejection::kNonFiniteEstimate, channel, in.pwm_us, in.voltage_v);
    }
  }
  return Rejection::kNone;
}

Totals Estimator::sumMotors(const std::uint16_t* channels, bool imu_fresh, double vertical_accel) {
  const bool tilt_known = imu_fresh && config_.compensate_tilt;
  Totals totals;
  totals.voltage_v = voltage_v_;
  double moment_x = 0.0, moment_y = 0.0;
  for (std::size_t i = 0; i < vehicle_.rotors.size(); ++i) {
    MotorOutput& motor = output_.motors[i];
    motor.pwm_us = channels[motor.channel - 1];
    motor.estimate = scratch_[i];
    const Rotor& rotor = vehicle_.rotors[i];
    const double thrust = motor.estimate.thrust_n;
    totals.thrust_n += thrust;
    totals.vertical_thrust_n += thrust * (tilt_known ? body_to_world_.row(2).dot(rotor.thrust_axis) : rotor.thrust_axis.z());
    totals.current_a += motor.estimate.current_a;
    totals.power_w += motor.estimate.power_w;
    totals.motors_out_of_domain += motor.estimate.in_domain ? 0 : 1;
    moment_x += thrust * rotor.position_m.x();
    moment_y += thrust * rotor.position_m.y();
  }
  const double accel_used = imu_fresh && config_.compensate_acceleration ? vertical_accel : 0.0;
  // NaN sums stand for what the model lacks; so does the efficiency without power or efficiency.
  totals.efficiency_n_per_w = !(has_power_ && has_efficiency_) ? kNaN
                              : totals.power_w > 0.0         ? totals.thrust_n / totals.power_w
                                                             : 0.0;
  totals.mass_kg = totals.vertical_thrust_n / (kStandardGravity + accel_used);
  totals.thrust_centre_x_m = totals.thrust_n > 0.0 ? moment_x / totals.thrust_n : kNaN;
  totals.thrust_centre_y_m = totals.thrust_n > 0.0 ? moment_y / totals.thrust_n : kNaN;
  return totals;
}

HoverSample Estimator::hoverSample(const Totals& totals, double receipt_s, bool imu_fresh, double vertical_accel,
                                   VerticalSpeedSource* speed_source) const {
  HoverSample sample;
  sample.vertical_thrust_n = totals.vertical_thrust_n;
  sample.mass_kg = totals.mass_kg;
  sample.tilt_rad = imu_fresh ? std::acos(std::clamp(body_to_world_(2, 2), -1.0, 1.0)) : kNaN;
  sample.vertical_speed_m_s = kNaN;
  if (velocityFresh(receipt_s)) {
    sample.vertical_speed_m_s = vertical_speed_m_s_;
    *speed_source = VerticalSpeedSource::kVelocity;
  } else if (!std::isnan(inputs_[input::index(input::Scalar::kStaticPressure)].at(
                 receipt_s, config_.inputTimeoutS(input::Scalar::kStaticPressure))) &&
             !std::isnan(barometric_speed_.value())) {
    sample.vertical_speed_m_s = barometric_speed_.value();
    *speed_source = VerticalSpeedSource::kBarometer;
  }
  sample.vertical_accel_m_s2 = vertical_accel;
  return sample;
}

void Estimator::countAccepted(double stamp_s, double receipt_s, const Totals& totals, effects::KindMask skipped) {
  const effects::ModelEffects& model_effects = model_.effects();
  for (effects::Kind kind : effects::kAllKinds) {
    if (!model_effects.has(kind)) continue;
    const std::size_t k = static_cast<std::size_t>(kind);
    ++((skipped & effects::bit(kind)) ? counters_.effect_skipped[k] : counters_.effect_applied[k]);
  }
  counters_.motor_samples += vehicle_.rotors.size();
  counters_.motor_samples_outside_domain += static_cast<std::uint64_t>(totals.motors_out_of_domain);
  ++counters_.accepted;
  last_stamp_s_ = stamp_s;
  have_stamp_ = true;
  last_accepted_receipt_s_ = receipt_s;
  have_accepted_ = true;
}

TareResult Estimator::tare(double now_s) {
  TareResult result;
  expireHover(now_s);
  const MassEstimate& estimate = payload_.estimate();
  const TareVerdict verdict = judgeTare(hover_.verdict(), estimate, config_);
  if (hover_.verdict().blocker == HoverBlocker::kExpired) {
    // The average is of a hover that may have ended on the ground (inputs stopped, then disarmed).
    std::ostringstream message;
    message.precision(3);
    message << "refused: no motor outputs accepted for " << now_s - last_accepted_receipt_s_
            << " s, longer than hover/window_s " << config_.hover.window_s << " s: the last hover verdict expired";
    result.message = message.str();
  } else if (!verdict.accepted) {
    result.message = verdict.refusal;
  } else {
    result.ok = true;
    result.empty_mass_kg = estimate.total_mass_kg;
    payload_.setEmptyMass(result.empty_mass_kg, EmptyMassSource::kTare);
    output_.payload = payload_.estimate();
    std::ostringstream message;
    message.precision(4);
    message << "empty mass " << result.empty_mass_kg << " kg (std " << estimate.mass_std_kg << " kg over "
            << estimate.window_samples << " samples, " << estimate.window_s << " s)";
    result.message = message.str();
  }
  return result;
}

void Estimator::setEffect(effects::Kind kind, std::optional<double> value) {
  effects::ModelEffects fx = model_.effects();
  if (value) {
    const effects::ParameterSpec& spec = effects::parameterSpec(kind);
    value = std::clamp(*value, spec.min, spec.max);
  }
  fx.setParameter(kind, value);
  model_ = model_.withEffects(fx);
}

void Estimator::setEmptyMass(double mass_kg, EmptyMassSource source) {
  payload_.setEmptyMass(mass_kg, source);
  output_.payload = payload_.estimate();
}

void Estimator::clearWindows() {
  hover_.clear();
  payload_.clearWindow();
  output_.hover = hover_.verdict();
  output_.payload = payload_.estimate();
}

void Estimator::reset() {
  clearWindows();
  accel_filter_.clear();
  have_stamp_ = false;
  if (configured_empty_mass_kg_) {
    payload_.setEmptyMass(*configured_empty_mass_kg_, configured_source_);
  } else {
    payload_.clearEmptyMass();
  }
  output_.payload = payload_.estimate();
}

std::string Estimator::describeHover() const { return describe(hover_.verdict(), config_.hover); }

}  // namespace propulsion_estimator
