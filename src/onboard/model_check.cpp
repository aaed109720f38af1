#include "propulsion_estimator/onboard/model_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "propulsion_estimator/common/field_error.h"

namespace propulsion_estimator {
namespace {

// A gap in the telemetry counts for at most this much of the average: a motor that was silent for
// a minute has not been measured for a minute.
constexpr double kMaxStepS = 0.5;
// How a healthy chain's input current follows its speed at a given voltage: shaft power ~ n^3
// (the propeller law), current ~ power / voltage. The current a motor draws for the speed it turns
// at tells a propeller's torque from the command's or the model's error at that command, which
// move speed and current together along this law.
constexpr double kCurrentSpeedExponent = 3.0;

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  if (n == 0) return kNaN;
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::vector<double> hoverRatios(const std::vector<MotorCheck>& motors) {
  std::vector<double> ratios;
  for (const MotorCheck& motor : motors) ratios.push_back(motor.hover_current_ratio);
  return ratios;
}

std::string percent(double ratio) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.1f %%", 100.0 * (ratio - 1.0));
  return text;
}

}  // namespace

void ModelCheckConfig::validate() const {
  requirePositive("esc_telemetry/stale_after_s", stale_after_s, 60.0, " s");
  requirePositive("esc_telemetry/window_s", window_s, 600.0, " s");
  requireWithin("esc_telemetry/min_hover_s", min_hover_s, 0.0, 600.0, " s");
  requirePositive("esc_telemetry/rpm_tolerance", rpm_tolerance, 1.0);
  requirePositive("esc_telemetry/current_tolerance", current_tolerance, 1.0);
  requirePositive("esc_telemetry/supply_tolerance", supply_tolerance, 1.0);
  requirePositive("esc_telemetry/supply_memory_s", supply_memory_s, 3600.0, " s");
  requirePositive("esc_telemetry/supply_voltage_sigma_v", supply_voltage_sigma_v, 10.0, " V");
  requirePositive("esc_telemetry/supply_max_rel_std", supply_max_rel_std, 1.0);
}

const char* modelCheckVerdictName(ModelCheckVerdict verdict) {
  switch (verdict) {
    case ModelCheckVerdict::kNotJudged: return "not_judged";
    case ModelCheckVerdict::kConsistent: return "consistent";
    case ModelCheckVerdict::kPropeller: return "propeller";
    case ModelCheckVerdict::kMotorEsc: return "motor_esc";
    case ModelCheckVerdict::kSupply: return "supply";
  }
  return "?";
}

const char* modelCheckAdvice(ModelCheckVerdict verdict) {
  switch (verdict) {
    case ModelCheckVerdict::kNotJudged: return "hover for a few seconds with ESC telemetry on every motor";
    case ModelCheckVerdict::kConsistent: return "nothing to do";
    case ModelCheckVerdict::kPropeller:
      return "land and inspect that motor's propeller (chipped, bent, loose or of another size or pitch)";
    case ModelCheckVerdict::kMotorEsc:
      return "land and check that motor (bearings, magnets, windings) and its ESC (settings, timing, heat)";
    case ModelCheckVerdict::kSupply:
      return "check the leads, connectors and power module between battery and ESCs, or model the air "
             "(air_density) and the supply (supply_resistance)";
  }
  return "";
}

ModelCheck::ModelCheck(std::vector<int> channels, ModelCheckConfig config)
    : config_(config), supply_(config.supply_memory_s, config.supply_voltage_sigma_v) {
  config_.validate();
  motors_.resize(channels.size());
  int highest = 0;
  for (int channel : channels) highest = std::max(highest, channel);
  esc_to_motor_.assign(static_cast<std::size_t>(highest), -1);
  for (std::size_t k = 0; k < channels.size(); ++k) {
    motors_[k].channel = channels[k];
    if (channels[k] >= 1) esc_to_motor_[static_cast<std::size_t>(channels[k] - 1)] = static_cast<int>(k);
  }
}

void ModelCheck::setBaseline(std::vector<double> rpm_deviation, std::vector<double> current_deviation,
                             double rpm_level) {
  if (rpm_deviation.size() != current_deviation.size() ||
      (!rpm_deviation.empty() && rpm_deviation.size() != motors_.size())) {
    throw std::invalid_argument("ESC baseline: " + std::to_string(rpm_deviation.size()) + " rpm and " +
                                std::to_string(current_deviation.size()) + " current deviations for " +
                                std::to_string(motors_.size()) + " rotors");
  }
  if (!std::isnan(rpm_level) && !(rpm_level > 0.0)) {
    throw std::invalid_argument("ESC baseline: rpm level " + std::to_string(rpm_level) + " is not positive");
  }
  baseline_rpm_level_ = std::isnan(rpm_level) ? 1.0 : rpm_level;
  baseline_log_rpm_.clear();
  baseline_log_current_.clear();
  for (std::size_t k = 0; k < rpm_deviation.size(); ++k) {
    baseline_log_rpm_.push_back(std::log1p(rpm_deviation[k]));
    baseline_log_current_.push_back(std::log1p(current_deviation[k]));
  }
}

void ModelCheck::reset() {
  for (Motor& motor : motors_) {
    const int channel = motor.channel;
    motor = Motor{};
    motor.channel = channel;
  }
  estimate_receipt_s_ = kNaN;
  hovering_ = false;
  supply_.reset();
}

bool ModelCheck::isNew(const Motor& motor, const EscReport& report) const {
  if (std::isnan(motor.last_receipt_s)) return true;
  if (report.count >= 0) return report.count != motor.last.count;
  return report.rpm != motor.last.rpm || report.current_a != motor.last.current_a ||
         report.voltage_v != motor.last.voltage_v;
}

void ModelCheck::addTelemetry(double receipt_s, const EscTelemetry& message) {
  telemetry_seen_ = true;
  const std::size_t escs = std::min(message.escs.size(), esc_to_motor_.size());
  for (std::size_t i = 0; i < escs; ++i) {
    if (esc_to_motor_[i] < 0) continue;
    Motor& motor = motors_[static_cast<std::size_t>(esc_to_motor_[i])];
    const EscReport& report = message.escs[i];
    if (!isNew(motor, report)) continue;
    motor.last = report;
    motor.last_receipt_s = receipt_s;
    compare(&motor, receipt_s);
  }
}

void ModelCheck::compare(Motor* motor, double receipt_s) {
  motor->rpm_ratio = motor->current_ratio = kNaN;
  // Compared only with an RCOut of the same moment, inside the model's domain.
  if (!(receipt_s - estimate_receipt_s_ <= config_.stale_after_s)) return;
  const EscReport& report = motor->last;
  if (motor->modelled_rpm > 0.0 && report.rpm > 0.0) motor->rpm_ratio = report.rpm / motor->modelled_rpm;
  if (motor->modelled_current_a > 0.0 && report.current_a > 0.0) {
    motor->current_ratio = report.current_a / motor->modelled_current_a;
  }
  if (!hovering_ || std::isnan(motor->rpm_ratio) || std::isnan(motor->current_ratio)) {
    motor->averaged_at_s = kNaN;
    return;
  }
  // Exponential average over window_s of each log ratio, weighted by the time each report stands for.
  const double step = std::isnan(motor->averaged_at_s) ? 0.0 : std::min(kMaxStepS, receipt_s - motor->averaged_at_s);
  const double weight = motor->averaged == 0 ? 1.0 : 1.0 - std::exp(-step / config_.window_s);
  motor->log_rpm += weight * (std::log(motor->rpm_ratio) - motor->log_rpm);
  motor->log_current += weight * (std::log(motor->current_ratio) - motor->log_current);
  motor->log_current_at_speed +=
      weight * (std::log(motor->current_ratio) - kCurrentSpeedExponent * std::log(motor->rpm_ratio) -
                motor->log_current_at_speed);
  motor->hover_s += step;
  ++motor->averaged;
  motor->averaged_at_s = receipt_s;
}

void ModelCheck::addEstimate(double receipt_s, const EstimatorOutput& output) {
  estimate_receipt_s_ = receipt_s;
  hovering_ = output.hover.hovering;
  const std::size_t n = std::min(motors_.size(), output.motors.size());
  for (std::size_t k = 0; k < n; ++k) {
    const OperatingPoint& estimate = output.motors[k].estimate;
    motors_[k].modelled_rpm = estimate.in_domain ? estimate.rpm : kNaN;
    motors_[k].modelled_current_a = estimate.in_domain ? estimate.current_a : kNaN;
  }
}

void ModelCheck::addBattery(double receipt_s, double voltage_v) {
  double esc_voltage = 0.0, current = 0.0;
  for (const Motor& motor : motors_) {
    if (!(receipt_s - motor.last_receipt_s <= config_.stale_after_s)) return;
    esc_voltage += motor.last.voltage_v;
    current += motor.last.current_a;
  }
  if (motors_.empty()) return;
  supply_.add(receipt_s, voltage_v - esc_voltage / static_cast<double>(motors_.size()), current);
}

double ModelCheck::supplyResistanceOhm() const {
  const double r = supply_.resistanceOhm(), std_ohm = supply_.resistanceStdOhm();
  return std_ohm <= config_.supply_max_rel_std * std::fabs(r) ? r : kNaN;
}

MotorCheck ModelCheck::motor(std::size_t k, double now_s) const {
  const Motor& motor = motors_[k];
  MotorCheck check;
  check.channel = motor.channel;
  if (now_s - motor.last_receipt_s <= config_.stale_after_s) {
    check.measured_rpm = motor.last.rpm;
    check.measured_current_a = motor.last.current_a;
    check.rpm_ratio = motor.rpm_ratio;
    check.current_ratio = motor.current_ratio;
  }
  check.hover_s = motor.hover_s;
  if (motor.averaged > 0) {
    check.hover_rpm_ratio = std::exp(motor.log_rpm);
    check.hover_current_ratio = std::exp(motor.log_current);
  }
  return check;
}

ModelCheckReport ModelCheck::report(double now_s) const {
  ModelCheckReport out;
  out.telemetry_seen = telemetry_seen_;
  out.supply_resistance_ohm = supply_.resistanceOhm();
  out.supply_resistance_std_ohm = supply_.resistanceStdOhm();
  out.supply_resistance_estimated = !std::isnan(supplyResistanceOhm());
  double least_hover_s = motors_.empty() ? 0.0 : motors_.front().hover_s;
  std::vector<double> log_rpm, log_current;
  for (std::size_t k = 0; k < motors_.size(); ++k) {
    const Motor& motor = motors_[k];
    const MotorCheck check = this->motor(k, now_s);
    if (!std::isnan(check.measured_rpm)) ++out.fresh_motors;
    least_hover_s = std::min(least_hover_s, motor.hover_s);
    log_rpm.push_back(motor.log_rpm - (baseline_log_rpm_.empty() ? 0.0 : baseline_log_rpm_[k]));
    log_current.push_back(motor.log_current_at_speed - (baseline_log_current_.empty() ? 0.0 : baseline_log_current_[k]));
    out.motors.push_back(check);
  }
  if (!telemetry_seen_) {
    out.note = "no ESC telemetry received";
    return out;
  }
  if (motors_.empty() || least_hover_s < config_.min_hover_s) {
    char text[160];
    std::snprintf(text, sizeof text, "%.1f s of hover with ESC telemetry on every motor, %.1f s needed", least_hover_s,
                  config_.min_hover_s);
    out.note = text;
    return out;
  }
  const double median_rpm = median(log_rpm), median_current = median(log_current);
  out.median_rpm_ratio = std::exp(median_rpm);
  out.median_current_ratio = median(hoverRatios(out.motors));
  double worst = 0.0;
  std::size_t flagged = 0;
  out.verdict = ModelCheckVerdict::kConsistent;
  for (std::size_t k = 0; k < motors_.size(); ++k) {
    MotorCheck& check = out.motors[k];
    check.rpm_deviation = std::exp(log_rpm[k] - median_rpm) - 1.0;
    check.current_deviation = std::exp(log_current[k] - median_current) - 1.0;
    check.verdict = ModelCheckVerdict::kConsistent;
    if (check.rpm_deviation > config_.rpm_tolerance && check.current_deviation < -config_.current_tolerance) {
      check.verdict = ModelCheckVerdict::kPropeller;
    } else if (check.rpm_deviation < -config_.rpm_tolerance && check.current_deviation > config_.current_tolerance) {
      check.verdict = ModelCheckVerdict::kMotorEsc;
    }
    if (check.verdict != ModelCheckVerdict::kConsistent && std::fabs(check.rpm_deviation) > worst) {
      worst = std::fabs(check.rpm_deviation);
      out.verdict = check.verdict;
      out.flagged_channel = check.channel;
      flagged = k;
    }
  }
  if (out.flagged_channel != 0) {
    const MotorCheck& motor = out.motors[flagged];
    out.note = std::string(modelCheckVerdictName(out.verdict)) + " on channel " + std::to_string(out.flagged_channel) +
               ": rpm " + percent(1.0 + motor.rpm_deviation) + ", current " + percent(1.0 + motor.current_deviation) +
               (baseline_log_rpm_.empty() ? " against the other motors" : " against the other motors and its healthy flights");
  } else if (std::fabs(out.median_rpm_ratio / baseline_rpm_level_ - 1.0) > config_.supply_tolerance) {
    out.verdict = ModelCheckVerdict::kSupply;
    out.note = "every motor alike off the model: rpm " + percent(out.median_rpm_ratio) + ", current " +
               percent(out.median_current_ratio) +
               (baseline_rpm_level_ != 1.0 ? " (" + percent(baseline_rpm_level_) + " on its healthy flights)" : "");
  } else {
    out.note = "every motor within tolerance of the model: rpm " + percent(out.median_rpm_ratio) + ", current " +
               percent(out.median_current_ratio);
  }
  return out;
}

}  // namespace propulsion_estimator
