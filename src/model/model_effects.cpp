#include "propulsion_estimator/model/model_effects.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace effects {
namespace {

// Ranges a real multicopter can show; a fit at a bound is reported as implausible.
//   supply_resistance: connectors, wires and a power module add 5-50 mOhm; a worn pack or
//     thin harness up to a few hundred.
//   air_density: thrust at fixed pulse width and voltage scales between rho^0.5 (a light, fast
//     motor gaining speed in thin air) and rho^1 (a stiff motor).
//   ground_effect: strength 0..2 of Cheeseman-Bennett on rotors up to 0.3 m in radius.
//   thrust_loss: arms and frame under the rotors take 2-10 %; more is a mis-built vehicle.
//   motor_temperature: copper +0.39 %/K and NdFeB flux -0.12 %/K move thrust by under 0.3 %/K.
//   climb_inflow: momentum theory gives about v / (2 v_hover) per m/s, a few % per m/s.
//   esc_offset: ESC calibrations differ by tens of microseconds.
constexpr std::array<ParameterSpec, kKindCount> kSpecs = {{
    {"resistance_ohm", 0.0, 0.5, 0.0},
    {"exponent", 0.0, 2.0, 0.0},
    {"coefficient_m2", 0.0, 0.02, 0.0},
    {"fraction", -0.1, 0.4, 0.0},
    {"per_c", -0.01, 0.01, 0.0},
    {"per_m_s", -0.1, 0.3, 0.0},
    {"offset_us", -100.0, 100.0, 0.0},
}};

int index(Kind kind) { return static_cast<int>(kind); }

}  // namespace

const char* kindName(Kind kind) {
  switch (kind) {
    case Kind::kSupplyResistance: return "supply_resistance";
    case Kind::kAirDensity: return "air_density";
    case Kind::kGroundEffect: return "ground_effect";
    case Kind::kThrustLoss: return "thrust_loss";
    case Kind::kMotorTemperature: return "motor_temperature";
    case Kind::kClimbInflow: return "climb_inflow";
    case Kind::kEscOffset: return "esc_offset";
  }
  return "?";
}

std::optional<Kind> kindFromName(const std::string& name) {
  for (Kind kind : kAllKinds) {
    if (name == kindName(kind)) return kind;
  }
  return std::nullopt;
}

Signal requiredSignal(Kind kind) {
  switch (kind) {
    case Kind::kSupplyResistance: return Signal::kBatteryCurrent;
    case Kind::kAirDensity: return Signal::kAirDensity;
    case Kind::kGroundEffect: return Signal::kHeight;
    case Kind::kMotorTemperature: return Signal::kMotorTemperature;
    case Kind::kClimbInflow: return Signal::kVerticalSpeed;
    case Kind::kThrustLoss:
    case Kind::kEscOffset: return Signal::kNone;
  }
  return Signal::kNone;
}

const char* signalName(Signal signal) {
  switch (signal) {
    case Signal::kNone: return "none";
    case Signal::kBatteryCurrent: return "battery current";
    case Signal::kAirDensity: return "air density (static pressure and air temperature)";
    case Signal::kHeight: return "height above the ground";
    case Signal::kMotorTemperature: return "motor temperature";
    case Signal::kVerticalSpeed: return "vertical speed";
  }
  return "?";
}

const ParameterSpec& parameterSpec(Kind kind) { return kSpecs[index(kind)]; }

double Signals::value(Signal signal) const {
  switch (signal) {
    case Signal::kBatteryCurrent: return battery_current_a;
    case Signal::kAirDensity: return air_density_kg_m3;
    case Signal::kHeight: return height_m;
    case Signal::kMotorTemperature: return motor_temperature_c;
    case Signal::kVerticalSpeed: return vertical_speed_m_s;
    case Signal::kNone: break;
  }
  return kNaN;
}

std::optional<double> ModelEffects::parameter(Kind kind) const {
  switch (kind) {
    case Kind::kSupplyResistance: return supply_resistance_ohm;
    case Kind::kAirDensity: return air_density_exponent;
    case Kind::kGroundEffect: return ground_effect_coefficient_m2;
    case Kind::kThrustLoss: return thrust_loss_fraction;
    case Kind::kMotorTemperature: return motor_temperature_per_c;
    case Kind::kClimbInflow: return climb_inflow_per_m_s;
    case Kind::kEscOffset: return esc_offset_us;
  }
  return std::nullopt;
}

void ModelEffects::setParameter(Kind kind, std::optional<double> value) {
  switch (kind) {
    case Kind::kSupplyResistance: supply_resistance_ohm = value; break;
    case Kind::kAirDensity: air_density_exponent = value; break;
    case Kind::kGroundEffect: ground_effect_coefficient_m2 = value; break;
    case Kind::kThrustLoss: thrust_loss_fraction = value; break;
    case Kind::kMotorTemperature: motor_temperature_per_c = value; break;
    case Kind::kClimbInflow: climb_inflow_per_m_s = value; break;
    case Kind::kEscOffset: esc_offset_us = value; break;
  }
}

bool ModelEffects::has(Kind kind) const { return parameter(kind).has_value(); }

bool ModelEffects::empty() const {
  return std::none_of(kAllKinds.begin(), kAllKinds.end(), [this](Kind kind) { return has(kind); });
}

void ModelEffects::validate() const {
  for (Kind kind : kAllKinds) {
    const std::optional<double> value = parameter(kind);
    if (!value) continue;
    const ParameterSpec& spec = parameterSpec(kind);
    requireWithin(std::string("effects.") + kindName(kind) + "." + spec.key, *value, spec.min, spec.max);
  }
  if (air_density_exponent && std::isnan(bench_air_density_kg_m3)) {
    throw FieldError("effects.air_density",
                     "needs the bench air of the model's metadata (bench_air_temperature_c, bench_air_pressure_pa) "
                     "as its reference, and the model has none");
  }
  if (air_density_exponent && !(bench_air_density_kg_m3 > 0.3 && bench_air_density_kg_m3 < 1.6)) {
    throw FieldError("effects.air_density", "the bench air density " + formatNumber(bench_air_density_kg_m3) +
                                                " kg/m^3 of the model's metadata is outside 0.3..1.6 kg/m^3");
  }
  if (motor_temperature_per_c) requireWithin("effects.motor_temperature.reference_c", motor_reference_c, -40.0, 150.0);
  if (ground_effect_coefficient_m2) requireWithin("effects.ground_effect.rotor_height_m", rotor_height_m, -1.0, 1.0);
}

std::string describeParameters(Kind kind, const ModelEffects& effects) {
  const std::optional<double> value = effects.parameter(kind);
  if (!value) return "off";
  std::string text = std::string(parameterSpec(kind).key) + " " + formatNumber(*value);
  switch (kind) {
    case Kind::kAirDensity:
      text += ", bench air " + formatPrintf("%.4f", effects.bench_air_density_kg_m3) + " kg/m^3";
      break;
    case Kind::kGroundEffect: text += ", rotor_height_m " + formatNumber(effects.rotor_height_m); break;
    case Kind::kMotorTemperature: text += ", reference_c " + formatNumber(effects.motor_reference_c); break;
    default: break;
  }
  return text;
}

Inputs correctInputs(const ModelEffects& effects, double pwm_us, double voltage_v, const Signals& signals,
                     KindMask* skipped) {
  Inputs inputs{pwm_us, voltage_v};
  if (effects.esc_offset_us) inputs.pwm_us -= *effects.esc_offset_us;
  if (effects.supply_resistance_ohm) {
    if (std::isfinite(signals.battery_current_a)) {
      inputs.voltage_v -= *effects.supply_resistance_ohm * signals.battery_current_a;
    } else if (skipped) {
      *skipped |= bit(Kind::kSupplyResistance);
    }
  }
  return inputs;
}

double singleThrustFactor(Kind kind, double value, const ModelEffects& references, const Signals& signals) {
  // Checked here, not left to the arithmetic: pow(NaN, 0) is 1, and an air_density exponent of 0
  // would count as applied without its signal.
  const Signal signal = requiredSignal(kind);
  if (signal != Signal::kNone && std::isnan(signals.value(signal))) return kNaN;
  switch (kind) {
    case Kind::kAirDensity:
      return std::pow(signals.air_density_kg_m3 / references.bench_air_density_kg_m3, value);
    case Kind::kGroundEffect: {
      const double distance = std::max(signals.height_m + references.rotor_height_m, kMinGroundDistanceM);
      return 1.0 + value / (distance * distance);
    }
    case Kind::kThrustLoss: return 1.0 - value;
    case Kind::kMotorTemperature: return 1.0 + value * (signals.motor_temperature_c - references.motor_reference_c);
    // Momentum theory: a climb's axial inflow lowers the blades' angle of attack, while a slow
    // descent (into the vortex-ring region) barely changes thrust at a given rotor speed.
    case Kind::kClimbInflow:
      return std::isnan(signals.vertical_speed_m_s) ? signals.vertical_speed_m_s
                                                     : 1.0 - value * std::max(signals.vertical_speed_m_s, 0.0);
    case Kind::kSupplyResistance:
    case Kind::kEscOffset: return 1.0;
  }
  return 1.0;
}

double thrustFactor(const ModelEffects& effects, const Signals& signals, KindMask* skipped) {
  double factor = 1.0;
  for (Kind kind : kAllKinds) {
    const std::optional<double> value = effects.parameter(kind);
    if (!value) continue;
    const double single = singleThrustFactor(kind, *value, effects, signals);
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
