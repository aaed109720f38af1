#include "propulsion_estimator/model/model_effects.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace effects {

// Each effect's file defines its describer (effect_list.h names them).
#define PE_EFFECT_DECLARE(enumerator, describer) const EffectDescription& describer();
PE_EFFECT_LIST(PE_EFFECT_DECLARE)
#undef PE_EFFECT_DECLARE

namespace {

using Describer = const EffectDescription& (*)();
constexpr std::array<Describer, kKindCount> kRegistry = {
#define PE_EFFECT_DESCRIBER(enumerator, describer) &describer,
    PE_EFFECT_LIST(PE_EFFECT_DESCRIBER)
#undef PE_EFFECT_DESCRIBER
};

int index(Kind kind) { return static_cast<int>(kind); }

}  // namespace

const EffectDescription& describe(Kind kind) { return kRegistry[index(kind)](); }

std::vector<std::string> allNames() {
  std::vector<std::string> names;
  for (Kind kind : kAllKinds) names.push_back(kindName(kind));
  return names;
}

const char* kindName(Kind kind) { return describe(kind).name; }

std::optional<Kind> kindFromName(const std::string& name) {
  for (Kind kind : kAllKinds) {
    if (name == kindName(kind)) return kind;
  }
  return std::nullopt;
}

Signal requiredSignal(Kind kind) { return describe(kind).signal; }

namespace {

// Each Signal's name for messages and key with its unit, in declaration order.
struct SignalText {
  const char* name;
  const char* key;
};
constexpr std::array<SignalText, kSignalCount> kSignalTexts = {{
    {"none", "none"},
    {"battery current", "battery_current_a"},
    {"air density", "air_density_kg_m3"},
    {"height above the ground", "height_m"},
    {"motor temperature", "motor_temperature_c"},
    {"vertical speed", "vertical_speed_m_s"},
    {"horizontal speed", "horizontal_speed_m_s"},
    {"speed along the rotors' axes", "axial_speed_m_s"},
}};

}  // namespace

const char* signalName(Signal signal) { return kSignalTexts[static_cast<int>(signal)].name; }

const char* signalKey(Signal signal) { return kSignalTexts[static_cast<int>(signal)].key; }

const std::array<Signal, kSignalCount - 1>& allSignals() {
  static const std::array<Signal, kSignalCount - 1> kSignals = {
      Signal::kBatteryCurrent, Signal::kAirDensity,      Signal::kHeight,    Signal::kMotorTemperature,
      Signal::kVerticalSpeed,  Signal::kHorizontalSpeed, Signal::kAxialSpeed};
  return kSignals;
}

const ParameterSpec& parameterSpec(Kind kind) { return describe(kind).parameter; }

std::optional<double> ModelEffects::parameter(Kind kind) const {
  if (!(on_ & bit(kind))) return std::nullopt;
  return values_[index(kind)];
}

void ModelEffects::setParameter(Kind kind, std::optional<double> value) {
  on_ = value ? on_ | bit(kind) : on_ & ~bit(kind);
  values_[index(kind)] = value.value_or(0.0);
}

bool ModelEffects::has(Kind kind) const { return parameter(kind).has_value(); }

bool ModelEffects::empty() const { return on_ == 0; }

void ModelEffects::validate() const {
  for (Kind kind : kAllKinds) {
    const std::optional<double> value = parameter(kind);
    if (!value) continue;
    const EffectDescription& description = describe(kind);
    requireWithin(std::string("effects.") + description.name + "." + description.parameter.key, *value,
                  description.parameter.min, description.parameter.max);
  }
  // The references after every parameter: a wrong parameter is named first.
  for (Kind kind : kAllKinds) {
    if (!has(kind)) continue;
    const EffectDescription& description = describe(kind);
    if (description.validate_reference) description.validate_reference(*this);
    const ReferenceSpec& reference = description.reference;
    if (reference.key) {
      requireWithin(std::string("effects.") + description.name + "." + reference.key, this->*reference.member,
                    reference.min, reference.max);
    }
  }
}

std::string describeParameters(Kind kind, const ModelEffects& effects) {
  const std::optional<double> value = effects.parameter(kind);
  if (!value) return "off";
  const EffectDescription& description = describe(kind);
  std::string text = std::string(description.parameter.key) + " " + formatNumber(*value);
  if (description.describe_reference) {
    text += description.describe_reference(effects);
  } else if (description.reference.key) {
    text += std::string(", ") + description.reference.key + " " + formatNumber(effects.*description.reference.member);
  }
  return text;
}

Inputs correctInputs(const ModelEffects& effects, double pwm_us, double voltage_v, const Signals& signals,
                     KindMask* skipped) {
  Inputs inputs{pwm_us, voltage_v};
  if (effects.empty()) return inputs;
  for (Kind kind : kAllKinds) {
    const std::optional<double> value = effects.parameter(kind);
    const EffectDescription& description = describe(kind);
    if (!value || !description.correct_inputs) continue;
    if (description.signal != Signal::kNone && std::isnan(signals.value(description.signal))) {
      if (skipped) *skipped |= bit(kind);
      continue;
    }
    inputs = description.correct_inputs(*value, inputs, signals);
  }
  return inputs;
}

double singleThrustFactor(Kind kind, double value, const ModelEffects& references, const Signals& signals,
                          double thrust_n) {
  // Checked here, not left to the arithmetic: an air_density exponent of 0 gives 1 without reading
  // the density, and would count as applied without its signal.
  const EffectDescription& description = describe(kind);
  if (description.signal != Signal::kNone && std::isnan(signals.value(description.signal))) return kNaN;
  return description.thrust_factor ? description.thrust_factor(value, references, signals, thrust_n) : 1.0;
}

double thrustFactor(const ModelEffects& effects, const Signals& signals, double thrust_n, KindMask* skipped) {
  double factor = 1.0;
  if (effects.empty()) return factor;
  for (Kind kind : kAllKinds) {
    const std::optional<double> value = effects.parameter(kind);
    if (!value) continue;
    const double single = singleThrustFactor(kind, *value, effects, signals, thrust_n);
    if (std::isfinite(single)) {
      factor *= single;
    } else if (skipped) {
      *skipped |= bit(kind);
    }
  }
  return factor;
}

}  // namespace effects
}  // namespace propulsion_estimator
