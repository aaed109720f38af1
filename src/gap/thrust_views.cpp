#include "propulsion_estimator/gap/thrust_views.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace gap {
namespace {

constexpr double kMaxShiftUs = 400.0;

}  // namespace

double currentViewExponent(effects::Kind kind, double parameter) {
  const effects::EffectDescription& description = effects::describe(kind);
  return description.current_view_exponent ? description.current_view_exponent(parameter) : 0.0;
}

double rpmViewExponent(effects::Kind kind, double parameter) {
  const effects::EffectDescription& description = effects::describe(kind);
  return description.rpm_view_exponent ? description.rpm_view_exponent(parameter) : 0.0;
}

ThrustViews::ThrustViews(const PropulsionModel& model, int motors, bool rpm_view)
    : model_(model),
      motors_(motors),
      thrust_to_si_(*unitToSi(Output::kThrust, model.output(Output::kThrust).unit)),
      has_current_(model.output(Output::kCurrent).source != OutputSource::kNone),
      rpm_view_(rpm_view) {
  motor_scale_.fill(1.0);
}

void ThrustViews::setLevels(double pwm, double current, double rpm) {
  pwm_level_ = std::isnan(pwm) ? 1.0 : pwm;
  current_level_ = std::isnan(current) ? 1.0 : current;
  rpm_level_ = std::isnan(rpm) ? 1.0 : rpm;
}

double ThrustViews::surfaceThrust(double pwm_us, double voltage_v) const { return offsetThrust(pwm_us, voltage_v, 0.0); }

double ThrustViews::offsetThrust(double pwm_us, double voltage_v, double offset_n) const {
  return std::max(0.0, model_.evaluateRaw(Output::kThrust, pwm_us, voltage_v) * thrust_to_si_ + offset_n);
}

double ThrustViews::motorThrust(double pwm_us, double voltage_v) const {
  OperatingPoint node;
  if (model_.domain().contains(pwm_us, voltage_v) || !model_.evaluate(pwm_us, voltage_v, &node)) {
    return surfaceThrust(pwm_us, voltage_v);
  }
  return node.thrust_n;
}

ThrustViews::Offset ThrustViews::outsideOffset(double pwm_us, double voltage_v) const {
  OperatingPoint node;
  if (model_.domain().contains(pwm_us, voltage_v) || !model_.evaluate(pwm_us, voltage_v, &node)) return {};
  Offset offset;
  offset.thrust_n = node.thrust_n - model_.evaluateRaw(Output::kThrust, pwm_us, voltage_v) * thrust_to_si_;
  if (has_current_) offset.current_a = node.current_a - model_.evaluateRaw(Output::kCurrent, pwm_us, voltage_v);
  return offset;
}

double ThrustViews::verticalThrust(const Block& block, double pwm_shift_us, const effects::Inputs* inputs,
                                   const Offset* offsets, const effects::ModelEffects* factors) const {
  double thrust = 0.0;
  for (int k = 0; k < motors_; ++k) {
    const double rotor = offsetThrust(inputs[k].pwm_us + pwm_shift_us, inputs[k].voltage_v, offsets[k].thrust_n);
    const double factor = factors ? effects::thrustFactor(*factors, block.signals, rotor) : 1.0;
    thrust += motor_scale_[k] * rotor * factor * block.axis_up[k];
  }
  return thrust;
}

std::array<ThrustViews::Offset, kMaxMotors> ThrustViews::offsets(const Block& block) const {
  std::array<Offset, kMaxMotors> offsets;
  for (int k = 0; k < motors_; ++k) offsets[k] = outsideOffset(block.pwm_us[k], block.voltage_v);
  return offsets;
}

double ThrustViews::pwmView(const Block& block, const effects::ModelEffects& effects) const {
  std::array<effects::Inputs, kMaxMotors> inputs;
  for (int k = 0; k < motors_; ++k) {
    inputs[k] = effects::correctInputs(effects, block.pwm_us[k], block.voltage_v, block.signals);
  }
  return pwm_level_ * verticalThrust(block, 0.0, inputs.data(), offsets(block).data(), &effects);
}

double ThrustViews::currentView(const Block& block, const effects::ModelEffects& effects) const {
  if (!has_current_ || !std::isfinite(block.current_a)) return kNaN;
  std::array<effects::Inputs, kMaxMotors> inputs;
  for (int k = 0; k < motors_; ++k) {
    inputs[k] = effects::correctInputs(effects, block.pwm_us[k], block.voltage_v, block.signals);
  }
  const std::array<Offset, kMaxMotors> offset = offsets(block);
  auto total_current = [&](double shift) {
    double current = 0.0;
    for (int k = 0; k < motors_; ++k) {
      current += std::max(0.0, model_.evaluateRaw(Output::kCurrent, inputs[k].pwm_us + shift, inputs[k].voltage_v) +
                                   offset[k].current_a);
    }
    return current;
  };
  // The current surface rises with pulse width over the usable range: bisection on the shift.
  double low = -kMaxShiftUs, high = kMaxShiftUs;
  if (total_current(low) > block.current_a || total_current(high) < block.current_a) return kNaN;
  for (int i = 0; i < 40; ++i) {
    const double middle = 0.5 * (low + high);
    (total_current(middle) < block.current_a ? low : high) = middle;
  }
  return current_level_ * verticalThrust(block, 0.5 * (low + high), inputs.data(), offset.data(), nullptr) *
         viewFactor(effects, block.signals, true);
}

double ThrustViews::rpmView(const Block& block, const effects::ModelEffects& effects) const {
  const std::optional<RpmThrust>& rpm_thrust = model_.rpmThrust();
  if (!rpm_view_ || !rpm_thrust) return kNaN;
  double thrust = 0.0;
  for (int k = 0; k < motors_; ++k) {
    if (!std::isfinite(block.rpm[k])) return kNaN;
    thrust += motor_scale_[k] * rpm_thrust->thrustN(block.rpm[k], block.signals.value(effects::Signal::kAirDensity)) * block.axis_up[k];
  }
  return rpm_level_ * thrust * viewFactor(effects, block.signals, false);
}

double ThrustViews::viewFactor(const effects::ModelEffects& effects, const effects::Signals& signals,
                               bool current_view) {
  if (effects.empty()) return 1.0;
  double factor = 1.0;
  for (effects::Kind kind : effects::kAllKinds) {
    const std::optional<double> value = effects.parameter(kind);
    const effects::EffectDescription& description = effects::describe(kind);
    // The input corrections reach the views through the surfaces.
    if (!value || !description.thrust_factor) continue;
    if (description.signal != effects::Signal::kNone && std::isnan(signals.value(description.signal))) continue;
    if (current_view && description.current_view_factor) {
      factor *= description.current_view_factor(*value, effects, signals);
      continue;
    }
    const double exponent = current_view ? currentViewExponent(kind, *value) : rpmViewExponent(kind, *value);
    // A view raises a factor to a power only for laws that do not read the rotor's thrust (the
    // air's, which does, has a current-view law of its own and none in the RPM view): NaN thrust
    // would show in the result, not pass unseen.
    if (exponent != 0.0) factor *= std::pow(effects::singleThrustFactor(kind, *value, effects, signals, kNaN), exponent);
  }
  return factor;
}

}  // namespace gap
}  // namespace propulsion_estimator
