#include "propulsion_estimator/onboard/capability.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/cells_in_series.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace {

// Charge steps of the hover discharge: three discharges (the estimate and its two spreads) of a
// few thousand model evaluations each, at 1 Hz.
constexpr int kDischargeSteps = 30;
// Fixed-point iterations of the full-throttle current and the voltage it sags to.
constexpr int kSagIterations = 6;
// Above this the motors run (A, all motors, modelled): the battery's current less the motors' is
// then what else the pack feeds, averaged over kUnmodelledMemoryS.
constexpr double kMotorsRunningA = 1.0;
constexpr double kUnmodelledMemoryS = 30.0;
// A pack temperature outside these (deg C) is not a reading (0 K, a sensor's fill value).
constexpr double kLowestPackC = -40.0;
constexpr double kHighestPackC = 90.0;
// The cold term of the interval: the whole of cold_capacity_rel at or below kColdPackC, none at or
// above kWarmPackC (a rule of thumb of LiPo practice: the capacity given falls below room
// temperature), linear between.
constexpr double kColdPackC = 10.0;
constexpr double kWarmPackC = 25.0;
// A percentage a smart battery reports as a share of the capacity: trusted to this.
constexpr double kReportedSocSigma = 0.02;

// Largest mass the thrust carries at the thrust-to-weight limit, less the present hover mass.
double additionalPayloadKg(double max_thrust_n, double min_thrust_to_weight, double hover_mass_kg) {
  return max_thrust_n / (kStandardGravity * min_thrust_to_weight) - hover_mass_kg;
}

}  // namespace

const char* percentageModeName(PercentageMode mode) {
  switch (mode) {
    case PercentageMode::kPx4Remaining: return "px4_remaining";
    case PercentageMode::kCapacityFraction: return "capacity_fraction";
    case PercentageMode::kIgnore: break;
  }
  return "ignore";
}

PercentageMode percentageModeFromName(const std::string& name) {
  for (PercentageMode mode : {PercentageMode::kIgnore, PercentageMode::kPx4Remaining, PercentageMode::kCapacityFraction}) {
    if (name == percentageModeName(mode)) return mode;
  }
  throw FieldError("capability/battery/percentage",
                   "\"" + name + "\" is not ignore, px4_remaining or capacity_fraction");
}

void CapabilityConfig::validate() const {
  requirePositive("capability/rate_hz", rate_hz);
  if (pwm_max_us) requirePositive("capability/pwm_max_us", *pwm_max_us);
  requirePositive("capability/min_thrust_to_weight", min_thrust_to_weight);
  if (capacity_ah) requirePositive("capability/battery/capacity_ah", *capacity_ah);
  if (cells) requireWithin("capability/battery/cells", *cells, kMinCellsInSeries, kMaxCellsInSeries);
  if (capacity_ah.has_value() != cells.has_value()) {
    throw FieldError(capacity_ah ? "capability/battery/cells" : "capability/battery/capacity_ah",
                     std::string("required with capability/battery/") + (capacity_ah ? "capacity_ah" : "cells"));
  }
  const OcvCurve ocv = curve();
  requirePositive("capability/battery/cell_cutoff_v", cell_cutoff_v);
  if (cell_cutoff_v >= ocv.fullCellV()) {
    throw FieldError("capability/battery/cell_cutoff_v", formatNumber(cell_cutoff_v) +
                                                             " V is not below the open-circuit curve's full " +
                                                             formatNumber(ocv.fullCellV()) + " V");
  }
  if (temperature_c) requireWithin("capability/battery/temperature_c", *temperature_c, kLowestPackC, kHighestPackC, " deg C");
  if (!(reserve_s >= 0.0) || std::isinf(reserve_s)) {
    throw FieldError("capability/reserve_s", "must be a non-negative number, got " + formatNumber(reserve_s));
  }
  motor_health.validate();
}

OcvCurve CapabilityConfig::curve() const {
  if (ocv_table_soc.empty() && ocv_table_cell_v.empty()) return OcvCurve::named(chemistry, "capability/battery/chemistry");
  return OcvCurve(ocv_table_soc, ocv_table_cell_v, "capability/battery/ocv_table");
}

std::optional<BatteryEstimatorConfig> CapabilityConfig::battery() const {
  if (!capacity_ah || !cells) return std::nullopt;
  BatteryEstimatorConfig battery;
  battery.cells = *cells;
  battery.capacity_ah = *capacity_ah;
  battery.curve = curve();
  if (pack) {
    battery.curve = learnedCurve(*pack, battery.curve);
    if (pack->capacity_ah) battery.capacity_ah = *pack->capacity_ah;
    if (!pack->resistance_ohm.empty()) battery.initial_resistance_ohm = pack->resistance_ohm.back();
    battery.rest_offset_cell_v = pack->rest_offset_cell_v.value_or(0.0);
  }
  return battery;
}

CapabilityEstimator::CapabilityEstimator(const PropulsionModel& model, int motors, CapabilityConfig config)
    : model_(model), motors_(motors), config_(std::move(config)) {
  config_.validate();
  pwm_max_us_ = config_.pwm_max_us.value_or(model_.domain().pwm_max_us);
  if (pwm_max_us_ <= model_.domain().pwm_min_us) {
    throw FieldError("capability/pwm_max_us", formatNumber(pwm_max_us_) + " us is not above the model's lowest PWM " +
                                                  formatNumber(model_.domain().pwm_min_us) + " us");
  }
  startBattery();
}

void CapabilityEstimator::addBattery(double time_s, double voltage_v, const BatteryReport& battery,
                                     double modelled_current_a) {
  measured_current_a_ = std::isfinite(battery.current_a) ? std::abs(battery.current_a) : kNaN;
  if (std::isfinite(measured_current_a_) && modelled_current_a > kMotorsRunningA && std::isfinite(time_s)) {
    const double unmodelled = measured_current_a_ - modelled_current_a;
    const double follow = std::isnan(unmodelled_s_) ? 1.0 : std::clamp((time_s - unmodelled_s_) / kUnmodelledMemoryS, 0.0, 1.0);
    unmodelled_current_a_ = std::isnan(unmodelled_current_a_) ? unmodelled
                                                              : unmodelled_current_a_ + follow * (unmodelled - unmodelled_current_a_);
    unmodelled_s_ = time_s;
  }
  const bool reported = battery.temperature_c >= kLowestPackC && battery.temperature_c <= kHighestPackC;
  temperature_c_ = reported ? battery.temperature_c : config_.temperature_c.value_or(kNaN);
  const bool known = battery.percentage >= 0.0 && battery.percentage <= 1.0;
  px4_remaining_ = config_.percentage == PercentageMode::kPx4Remaining && known ? battery.percentage : kNaN;
  if (!battery_) return;
  battery_read_ = true;
  const double current_a = std::isfinite(measured_current_a_) ? measured_current_a_ : modelled_current_a;
  battery_->add(time_s, voltage_v, current_a);
  learner_->add(time_s, voltage_v, current_a, battery_->estimate());
  if (config_.percentage == PercentageMode::kCapacityFraction && known) {
    battery_->addStateOfCharge(battery.percentage, kReportedSocSigma);
  }
}

void CapabilityEstimator::startBattery() {
  const std::optional<BatteryEstimatorConfig> battery = config_.battery();
  if (!battery) return;
  battery_.emplace(*battery);
  PackLearnerConfig learner;
  learner.cells = battery->cells;
  learner.capacity_ah = battery->capacity_ah;
  learner.rest_current_a = battery->rest_current_a;  // one rest for the estimator and the learner
  learner_.emplace(learner);
}

bool CapabilityEstimator::usePack(const PackRecord& record) {
  if (!battery_ || battery_read_) return false;
  config_.pack = record;
  startBattery();
  return true;
}

double CapabilityEstimator::packRestLeftS() const { return learner_ ? learner_->restLeftS() : kNaN; }

PackRecord CapabilityEstimator::learnPack(const PackRecord& previous) {
  if (!packFlightFinished()) return previous;
  PackRecord record = learner_->learned(previous, battery_->config().curve);
  learner_->startNextFlight();
  return record;
}

OperatingPoint CapabilityEstimator::fullThrottle(double voltage_v, const Correction& correction) const {
  Correction at = correction;
  OperatingPoint e;
  double total_a = 0.0;
  // The supply resistance's drop depends on the current it sets.
  for (int k = 0; k < kSagIterations; ++k) {
    at.signals.set(effects::Signal::kBatteryCurrent, total_a);
    if (!evaluateCorrected(model_, at, pwm_max_us_, voltage_v, &e)) return OperatingPoint{kNaN, kNaN, kNaN, kNaN, kNaN, false};
    total_a = motors_ * (std::isfinite(e.current_a) ? e.current_a : 0.0);
  }
  e.thrust_n *= motors_;
  e.current_a *= motors_;
  return e;
}

void CapabilityEstimator::evaluatePayload(const Correction& correction, CapabilityReport* c) const {
  if (std::isnan(c->voltage_v)) {
    c->payload_note = "no motor output yet";
    return;
  }
  // The voltage the pack sags to at full throttle: its open-circuit voltage less its internal
  // resistance times the full-throttle current, solved together. Without a converged battery
  // estimate, the voltage measured now (an optimistic limit: the note says so).
  double voltage = c->voltage_v;
  OperatingPoint top = fullThrottle(voltage, correction);
  if (battery_) {
    const std::string withheld = battery_->withheldReason();
    if (withheld.empty() && std::isfinite(top.current_a)) {
      const BatteryEstimate& b = battery_->estimate();
      for (int k = 0; k < kSagIterations && std::isfinite(top.current_a); ++k) {
        voltage = b.open_circuit_voltage_v - b.internal_resistance_ohm * top.current_a;
        top = fullThrottle(voltage, correction);
      }
      c->payload_sagged = true;
    } else {
      c->payload_note = "at the voltage measured now, not sagged to full throttle: " +
                        (withheld.empty() ? std::string("the model has no current") : withheld);
    }
  }
  c->full_throttle_voltage_v = voltage;
  c->full_throttle_current_a = top.current_a;
  c->max_thrust_n = top.thrust_n;
  if (std::isnan(c->max_thrust_n)) c->payload_note = "the model rejects " + formatPrintf("%.2f V", voltage);
  if (battery_) {
    c->max_thrust_at_cutoff_n = fullThrottle(c->cutoff_voltage_v, correction).thrust_n;
    if (std::isnan(c->max_thrust_at_cutoff_n) && c->payload_note.empty()) {
      c->payload_note = "the model rejects the cut-off " + formatPrintf("%.2f V", c->cutoff_voltage_v);
    }
  } else if (c->payload_note.empty()) {
    c->payload_note = "at the present voltage, no sag, and no cut-off figures: no battery configured "
                      "(capability/battery/capacity_ah, cells)";
  }
}

CapabilityReport CapabilityEstimator::evaluate(const EstimatorOutput& output, const effects::Signals& signals) const {
  CapabilityReport c;
  c.pwm_max_us = pwm_max_us_;
  const MassEstimate& payload = output.payload;
  c.voltage_v = output.totals.voltage_v > 0.0 ? output.totals.voltage_v : kNaN;
  c.hover_mass_kg = payload.total_mass_kg;
  c.hover_basis = std::isnan(payload.total_mass_kg)
                      ? std::string("no hover yet")
                      : formatPrintf("%.1f", payload.window_s) + " s of hover (" + payloadStateName(payload.state) + ")";
  if (battery_) c.cutoff_voltage_v = battery_->config().cells * config_.cell_cutoff_v;
  Correction correction{&model_.effects(), signals};
  correction.signals.set(effects::Signal::kVerticalSpeed, 0.0);
  evaluatePayload(correction, &c);
  if (std::isnan(c.hover_mass_kg)) {
    c.payload_note = "no hover yet";
  } else {
    const double weight_n = c.hover_mass_kg * kStandardGravity;
    c.thrust_to_weight = c.max_thrust_n / weight_n;
    c.max_additional_payload_kg = additionalPayloadKg(c.max_thrust_n, config_.min_thrust_to_weight, c.hover_mass_kg);
    c.thrust_to_weight_at_cutoff = c.max_thrust_at_cutoff_n / weight_n;
    c.max_additional_payload_at_cutoff_kg =
        additionalPayloadKg(c.max_thrust_at_cutoff_n, config_.min_thrust_to_weight, c.hover_mass_kg);
    c.payload_over_limit = c.max_additional_payload_kg < 0.0;
    if (!std::isnan(c.voltage_v)) {
      Correction at = correction;
      at.signals.set(effects::Signal::kBatteryCurrent, measured_current_a_);
      if (!std::isfinite(at.signals.value(effects::Signal::kBatteryCurrent))) at.signals.set(effects::Signal::kBatteryCurrent, output.totals.current_a);
      const std::optional<HoverPoint> hover = hoverPoint(model_, weight_n / motors_, c.voltage_v, at);
      if (hover) {
        c.hover_pwm_us = hover->pwm_us;
        c.hover_current_a = motors_ * hover->current_a;
      }
    }
  }
  c.unmodelled_current_a = unmodelled_current_a_;
  evaluateEndurance(correction, &c);
  c.endurance_below_reserve = c.hover_endurance_s < config_.reserve_s;
  return c;
}

HoverDischarge CapabilityEstimator::discharge(double state_of_charge, double resistance_ohm, double thrust_per_motor_n,
                                              const Correction& correction) const {
  const BatteryEstimatorConfig& b = battery_->config();
  DischargePack pack;
  const double capacity_ah = b.capacity_ah;
  const OcvCurve& curve = b.curve;
  const int cells = b.cells;
  pack.open_circuit_v = [&curve, cells, capacity_ah, state_of_charge](double drawn_ah) {
    return cells * curve.cellVoltage(state_of_charge - drawn_ah / capacity_ah);
  };
  pack.charge_ah = state_of_charge * capacity_ah;
  pack.resistance_ohm = resistance_ohm;
  pack.cutoff_voltage_v = cells * config_.cell_cutoff_v;
  pack.other_current_a = std::isfinite(unmodelled_current_a_) ? unmodelled_current_a_ : 0.0;
  if (!std::isnan(px4_remaining_)) {
    // PX4's remaining already runs to its own empty voltage: the charge is drawn to its end.
    pack.charge_ah = px4_remaining_ * capacity_ah;
    pack.cutoff_voltage_v = 0.0;
  }
  return integrateHoverDischarge(model_, pack, thrust_per_motor_n, motors_, kDischargeSteps, correction);
}

void CapabilityEstimator::evaluateEndurance(const Correction& correction, CapabilityReport* c) const {
  if (!battery_) {
    c->charge_basis = c->endurance_basis = "no battery capacity configured (capability/battery/capacity_ah, cells)";
    return;
  }
  const BatteryEstimate& b = battery_->estimate();
  c->state_of_charge = b.state_of_charge;
  c->state_of_charge_std = b.state_of_charge_std;
  c->internal_resistance_ohm = b.internal_resistance_ohm;
  c->internal_resistance_std_ohm = b.internal_resistance_std_ohm;
  c->open_circuit_voltage_v = b.open_circuit_voltage_v;
  const bool px4 = !std::isnan(px4_remaining_);
  c->charge_basis = px4 ? std::string("px4_remaining")
                        : std::string("open-circuit curve") +
                              (config_.percentage == PercentageMode::kCapacityFraction ? ", capacity_fraction" : "") +
                              (std::isnan(measured_current_a_) ? "" : " and coulomb counting");
  if (std::isnan(c->hover_mass_kg)) {
    c->endurance_basis = "no hover yet";
    return;
  }
  const std::string withheld = battery_->withheldReason();
  if (!withheld.empty() && !px4) {
    c->endurance_basis = "withheld: " + withheld;
    return;
  }
  if (model_.output(Output::kCurrent).source == OutputSource::kNone) {
    evaluateEnduranceAtMeasuredCurrent(c);
    return;
  }
  const double thrust_per_motor_n = c->hover_mass_kg * kStandardGravity / motors_;
  const double resistance = px4 ? 0.0 : b.internal_resistance_ohm;
  const HoverDischarge nominal = discharge(b.state_of_charge, resistance, thrust_per_motor_n, correction);
  if (!nominal.endurance_s) {
    c->endurance_basis = nominal.notes.empty() ? std::string("the hover discharge did not reach the cut-off")
                                               : nominal.notes.back();
    return;
  }
  c->hover_endurance_s = *nominal.endurance_s;
  double previous_s = 0.0;
  c->remaining_ah = 0.0;
  for (const DischargeStep& step : nominal.steps) {
    c->remaining_ah += (step.time_s - previous_s) * step.total_current_a / 3600.0;
    previous_s = step.time_s;
  }
  c->endurance_basis = px4 ? "PX4's remaining drawn at the model's hover current"
                           : "to the loaded cut-off at the model's hover current, internal resistance included";
  if (std::isfinite(unmodelled_current_a_)) {
    c->endurance_basis += ", " + formatPrintf("%.2f A", unmodelled_current_a_) + " beyond the motors' (measured less modelled)";
  }
  if (px4) return;
  // The spread: the endurance at one standard deviation less charge (the estimate's and where the
  // pack's knee lies against the curve's), at one more resistance, and the capacity's.
  const BatteryEstimatorConfig& pack = battery_->config();
  const double charge_std = std::hypot(b.state_of_charge_std, pack.knee_soc_std);
  const auto shorter_by = [&](double state_of_charge, double resistance_ohm) {
    const HoverDischarge d = discharge(std::clamp(state_of_charge, 0.0, 1.0), resistance_ohm, thrust_per_motor_n, correction);
    return c->hover_endurance_s - d.endurance_s.value_or(0.0);
  };
  const double by_charge = shorter_by(b.state_of_charge - charge_std, resistance);
  const double by_resistance = shorter_by(b.state_of_charge, resistance + b.internal_resistance_std_ohm);
  // The capacity's own spread scales the whole endurance.
  const double by_capacity = c->hover_endurance_s * pack.capacity_rel_std;
  c->hover_endurance_std_s = std::sqrt(by_charge * by_charge + by_resistance * by_resistance + by_capacity * by_capacity);
  // The interval's low end also holds what only lowers the endurance: the polarisation still to
  // build on a pack's first minutes, and a cold pack's lost capacity (its temperature unknown).
  const double unseen_ohm = resistance * pack.polarisation_rel * std::exp(-b.loaded_s / pack.polarisation_time_s);
  const double by_polarisation = shorter_by(b.state_of_charge, resistance + b.internal_resistance_std_ohm + unseen_ohm);
  const double coldness = std::isnan(temperature_c_)
                              ? 1.0
                              : std::clamp((kWarmPackC - temperature_c_) / (kWarmPackC - kColdPackC), 0.0, 1.0);
  const double by_cold = c->hover_endurance_s * pack.cold_capacity_rel * coldness;
  c->endurance_basis += std::isnan(temperature_c_)
                            ? "; pack temperature unknown: the interval allows for a cold pack"
                            : "; pack at " + formatPrintf("%.0f deg C", temperature_c_);
  const double by_more_charge = -shorter_by(b.state_of_charge + charge_std, resistance);
  const double low = std::sqrt(by_charge * by_charge + by_polarisation * by_polarisation + by_capacity * by_capacity +
                               by_cold * by_cold);
  const double high = std::sqrt(by_more_charge * by_more_charge + by_resistance * by_resistance + by_capacity * by_capacity);
  c->hover_endurance_low_s = std::max(0.0, c->hover_endurance_s - pack.interval_low_z * low);
  c->hover_endurance_high_s = c->hover_endurance_s + pack.interval_high_z * high;
}

void CapabilityEstimator::evaluateEnduranceAtMeasuredCurrent(CapabilityReport* c) const {
  const double current_a = measured_current_a_;
  if (!(current_a > 0.0) || std::isinf(current_a)) {
    c->endurance_basis = "no current surface and no current measured";
    return;
  }
  // The measured current held: the charge left until the loaded voltage at that current reaches
  // the cut-off (or PX4's remaining).
  const BatteryEstimate& b = battery_->estimate();
  const BatteryEstimatorConfig& pack = battery_->config();
  c->hover_current_a = current_a;
  if (!std::isnan(px4_remaining_)) {
    c->remaining_ah = px4_remaining_ * pack.capacity_ah;
  } else {
    const double cut_soc =
        pack.curve.stateOfCharge(config_.cell_cutoff_v + b.internal_resistance_ohm * current_a / pack.cells);
    c->remaining_ah = std::max(0.0, b.state_of_charge - cut_soc) * pack.capacity_ah;
  }
  c->hover_endurance_s = 3600.0 * c->remaining_ah / current_a;
  c->endurance_basis = "measured current " + formatPrintf("%.1f A", current_a) + " held, charge from " + c->charge_basis;
}

HealthStatus judgeCapability(const CapabilityReport& c, const MotorHealthVerdict& health, const CapabilityConfig& config) {
  HealthStatus status;
  const auto value = [&status](const std::string& key, double v) { status.values.emplace_back(key, formatNumber(v)); };
  value("hover mass (kg)", c.hover_mass_kg);
  value("max thrust (N)", c.max_thrust_n);
  value("thrust to weight", c.thrust_to_weight);
  value("max additional payload (kg)", c.max_additional_payload_kg);
  value("max additional payload at cut-off (kg)", c.max_additional_payload_at_cutoff_kg);
  if (!c.payload_note.empty()) status.values.emplace_back("payload note", c.payload_note);
  value("hover endurance (s)", c.hover_endurance_s);
  value("hover endurance std (s)", c.hover_endurance_std_s);
  value("hover endurance 90 % low (s)", c.hover_endurance_low_s);
  value("hover endurance 90 % high (s)", c.hover_endurance_high_s);
  value("state of charge", c.state_of_charge);
  value("internal resistance (ohm)", c.internal_resistance_ohm);
  status.values.emplace_back("endurance basis", c.endurance_basis);
  status.values.emplace_back("motor health", health.judged ? "judged" : health.unavailable);
  for (const MotorBalanceGap& motor : health.motors) {
    status.values.emplace_back("channel " + std::to_string(motor.channel) + " thrust gap (%)",
                               formatPrintf("%.1f", 100.0 * motor.thrust_gap) + " +- " +
                                   formatPrintf("%.1f", 100.0 * motor.thrust_gap_std));
  }
  value("cg offset x (m)", health.cg_offset_x_m);
  value("cg offset y (m)", health.cg_offset_y_m);

  std::vector<std::string> warnings;
  if (c.payload_over_limit) {
    warnings.push_back("payload " + formatPrintf("%.3f kg", -c.max_additional_payload_kg) +
                       " over the limit (thrust to weight " + formatPrintf("%.2f", c.thrust_to_weight) + " < " +
                       formatPrintf("%.2f", config.min_thrust_to_weight) + ")");
  }
  if (c.endurance_below_reserve) {
    warnings.push_back("hover endurance " + formatPrintf("%.0f s", c.hover_endurance_s) + " below the reserve " +
                       formatPrintf("%.0f s", config.reserve_s));
  }
  if (health.flagged_channel != 0) {
    for (const MotorBalanceGap& motor : health.motors) {
      if (motor.channel != health.flagged_channel) continue;
      warnings.push_back("motor on channel " + std::to_string(motor.channel) + " gives " +
                         formatPrintf("%.1f", 100.0 * motor.thrust_gap) + " +- " +
                         formatPrintf("%.1f", 100.0 * motor.thrust_gap_std) +
                         " % less thrust than modelled (steady-hover moment balance)");
    }
  }
  if (!warnings.empty()) {
    status.level = HealthLevel::kWarn;
    for (std::size_t k = 0; k < warnings.size(); ++k) status.message += (k ? "; " : "") + warnings[k];
    return status;
  }
  status.message = "max additional payload " +
                   (std::isnan(c.max_additional_payload_kg) ? "unknown (" + c.payload_note + ")"
                    : formatPrintf("%.3f kg", c.max_additional_payload_kg) +
                          (c.payload_sagged ? "" : " at the present voltage, no sag")) +
                   ", hover endurance " +
                   (std::isnan(c.hover_endurance_s) ? "unknown (" + c.endurance_basis + ")"
                                                    : formatPrintf("%.0f s", c.hover_endurance_s) +
                                                          (std::isnan(c.hover_endurance_low_s)
                                                               ? std::string()
                                                               : formatPrintf(" (90 %%: %.0f", c.hover_endurance_low_s) +
                                                                     formatPrintf("-%.0f s)", c.hover_endurance_high_s)));
  if (health.judged) {
    status.message += ", motors balanced, centre of gravity " +
                      formatPrintf("%.1f", 100.0 * std::hypot(health.cg_offset_x_m, health.cg_offset_y_m)) +
                      " cm off the URDF's";
  }
  return status;
}

}  // namespace propulsion_estimator
