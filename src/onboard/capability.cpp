#include "propulsion_estimator/onboard/capability.h"

#include <cmath>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace {

// Charge steps of the hover discharge: a 1 Hz evaluation of a few thousand model evaluations.
constexpr int kDischargeSteps = 50;

// Largest mass the thrust carries at the thrust-to-weight limit, less the present hover mass.
double additionalPayloadKg(double max_thrust_n, double min_thrust_to_weight, double hover_mass_kg) {
  return max_thrust_n / (kStandardGravity * min_thrust_to_weight) - hover_mass_kg;
}

}  // namespace

void CapabilityConfig::validate() const {
  requirePositive("capability/rate_hz", rate_hz);
  if (pwm_max_us) requirePositive("capability/pwm_max_us", *pwm_max_us);
  requirePositive("capability/min_thrust_to_weight", min_thrust_to_weight);
  if (capacity_ah) requirePositive("capability/battery/capacity_ah", *capacity_ah);
  if (cells && (*cells < 1 || *cells > 14)) {
    throw FieldError("capability/battery/cells", std::to_string(*cells) + " is outside 1..14");
  }
  if (capacity_ah.has_value() != cells.has_value()) {
    throw FieldError(capacity_ah ? "capability/battery/cells" : "capability/battery/capacity_ah",
                     std::string("required with capability/battery/") + (capacity_ah ? "capacity_ah" : "cells"));
  }
  if (!(usable_fraction > 0.0 && usable_fraction <= 1.0)) {
    throw FieldError("capability/battery/usable_fraction", formatNumber(usable_fraction) + " is outside (0, 1]");
  }
  requirePositive("capability/battery/cell_full_v", cell_full_v);
  requirePositive("capability/battery/cell_cutoff_v", cell_cutoff_v);
  if (cell_cutoff_v >= cell_full_v) {
    throw FieldError("capability/battery/cell_cutoff_v", formatNumber(cell_cutoff_v) +
                                                             " V is not below capability/battery/cell_full_v " +
                                                             formatNumber(cell_full_v) + " V");
  }
  if (!(reserve_s >= 0.0) || std::isinf(reserve_s)) {
    throw FieldError("capability/reserve_s", "must be a non-negative number, got " + formatNumber(reserve_s));
  }
  motor_health.validate();
}

std::optional<BatteryPack> CapabilityConfig::pack() const {
  if (!capacity_ah || !cells) return std::nullopt;
  return BatteryPack{*cells, *capacity_ah, usable_fraction, cell_full_v, cell_cutoff_v};
}

CapabilityEstimator::CapabilityEstimator(const PropulsionModel& model, int motors, CapabilityConfig config)
    : model_(model), motors_(motors), config_(std::move(config)) {
  config_.validate();
  pwm_max_us_ = config_.pwm_max_us.value_or(model_.domain().pwm_max_us);
  if (pwm_max_us_ <= model_.domain().pwm_min_us) {
    throw FieldError("capability/pwm_max_us", formatNumber(pwm_max_us_) + " us is not above the model's lowest PWM " +
                                                  formatNumber(model_.domain().pwm_min_us) + " us");
  }
}

double CapabilityEstimator::maxThrustN(double voltage_v) const {
  OperatingPoint e;
  if (!model_.evaluate(pwm_max_us_, voltage_v, &e)) return kNaN;
  return motors_ * e.thrust_n;
}

CapabilityReport CapabilityEstimator::evaluate(const EstimatorOutput& output, const BatteryReport& battery) const {
  CapabilityReport c;
  c.pwm_max_us = pwm_max_us_;
  const MassEstimate& payload = output.payload;
  c.voltage_v = output.totals.voltage_v > 0.0 ? output.totals.voltage_v : kNaN;
  c.hover_mass_kg = payload.total_mass_kg;
  c.hover_basis = std::isnan(payload.total_mass_kg)
                      ? std::string("no hover yet")
                      : formatPrintf("%.1f", payload.window_s) + " s of hover (" + payloadStateName(payload.state) + ")";
  const std::optional<BatteryPack> pack = config_.pack();
  if (pack) c.cutoff_voltage_v = pack->cutoffVoltage();

  if (std::isnan(c.voltage_v)) {
    c.payload_note = "no motor output yet";
  } else {
    c.max_thrust_n = maxThrustN(c.voltage_v);
    if (std::isnan(c.max_thrust_n)) c.payload_note = "the model rejects " + formatPrintf("%.2f V", c.voltage_v);
  }
  if (pack) {
    c.max_thrust_at_cutoff_n = maxThrustN(pack->cutoffVoltage());
    if (std::isnan(c.max_thrust_at_cutoff_n) && c.payload_note.empty()) {
      c.payload_note = "the model rejects the cut-off " + formatPrintf("%.2f V", pack->cutoffVoltage());
    }
  } else if (c.payload_note.empty()) {
    c.payload_note = "no cut-off figures: no battery configured (capability/battery/capacity_ah, cells)";
  }
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
      const std::optional<HoverPoint> hover = hoverPoint(model_, weight_n / motors_, c.voltage_v);
      if (hover) {
        c.hover_pwm_us = hover->pwm_us;
        c.hover_current_a = motors_ * hover->current_a;
      }
    }
  }
  evaluateEndurance(battery, &c);
  c.endurance_below_reserve = c.hover_endurance_s < config_.reserve_s;
  return c;
}

void CapabilityEstimator::evaluateEndurance(const BatteryReport& battery, CapabilityReport* c) const {
  const std::optional<BatteryPack> pack = config_.pack();
  if (!pack) {
    c->charge_basis = c->endurance_basis = "no battery capacity configured (capability/battery/capacity_ah, cells)";
    return;
  }
  double drawn_ah = kNaN;
  if (battery.percentage >= 0.0 && battery.percentage <= 1.0) {
    drawn_ah = pack->drawnAtStateOfCharge(battery.percentage);
    c->state_of_charge = battery.percentage;
    c->charge_basis = "percentage";
  } else if (battery.charge_ah >= 0.0 && std::isfinite(battery.charge_ah)) {
    c->state_of_charge = battery.charge_ah / pack->capacity_ah;
    drawn_ah = pack->drawnAtStateOfCharge(c->state_of_charge);
    c->charge_basis = "charge";
  } else if (!std::isnan(c->voltage_v)) {
    drawn_ah = pack->drawnAt(c->voltage_v);
    c->state_of_charge = 1.0 - drawn_ah / pack->capacity_ah;
    c->charge_basis = "voltage";
  } else {
    c->charge_basis = c->endurance_basis = "no battery state yet";
    return;
  }
  c->remaining_ah = pack->usableAh() - drawn_ah;
  if (std::isnan(c->hover_mass_kg)) {
    c->endurance_basis = "no hover yet";
    return;
  }
  const double thrust_per_motor_n = c->hover_mass_kg * kStandardGravity / motors_;
  if (model_.output(Output::kCurrent).source != OutputSource::kNone) {
    // From the voltage measured now, under the hover load: the linear discharge's voltages where
    // the real pack's differ most (its plateau) would misplace the hover currents.
    const HoverDischarge discharge = integrateHoverDischarge(model_, c->voltage_v, pack->cutoffVoltage(),
                                                             c->remaining_ah, thrust_per_motor_n, motors_,
                                                             kDischargeSteps);
    if (discharge.endurance_s) {
      c->hover_endurance_s = *discharge.endurance_s;
      c->endurance_basis = "model current at the hover point, charge from " + c->charge_basis;
    } else {
      c->endurance_basis = discharge.notes.empty() ? std::string("the hover discharge did not reach the cut-off")
                                                   : discharge.notes.back();
    }
    return;
  }
  const double current_a = std::abs(battery.current_a);
  if (!(current_a > 0.0) || std::isinf(current_a)) {
    c->endurance_basis = "no current surface and no current measured";
    return;
  }
  c->hover_current_a = current_a;
  c->hover_endurance_s = 3600.0 * c->remaining_ah / current_a;
  c->endurance_basis = "measured current " + formatPrintf("%.1f A", current_a) + ", charge from " + c->charge_basis;
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
                                                            : formatPrintf("%.3f kg", c.max_additional_payload_kg)) +
                   ", hover endurance " +
                   (std::isnan(c.hover_endurance_s) ? "unknown (" + c.endurance_basis + ")"
                                                    : formatPrintf("%.0f s", c.hover_endurance_s));
  if (health.judged) {
    status.message += ", motors balanced, centre of gravity " +
                      formatPrintf("%.1f", 100.0 * std::hypot(health.cg_offset_x_m, health.cg_offset_y_m)) +
                      " cm off the URDF's";
  }
  return status;
}

}  // namespace propulsion_estimator
