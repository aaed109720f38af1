#include "propulsion_estimator/sim/physics/sim_effects.h"

#include <algorithm>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace {

// An effect's parameter is checked only when the effect is on.
void requireWithinIfOn(const std::optional<double>& value, const char* field, double lo, double hi, const char* unit) {
  if (value) requireWithin(field, *value, lo, hi, unit);
}

}  // namespace

void SimEffects::validate() const {
  requireWithinIfOn(supply_resistance_ohm, "supply_resistance.ohm", 0.0, 1.0, " ohm");
  if (air) air->validate("air_density");
  requireWithinIfOn(ground_effect_strength, "ground_effect.strength", 0.0, 5.0, "");
  requireWithinIfOn(thrust_loss_fraction, "thrust_loss.fraction", 0.0, 0.5, "");
  requireWithinIfOn(motor_thermal_resistance_c_per_w, "motor_temperature.thermal_resistance_c_per_w", 0.01, 100.0,
                    " deg C/W");
  // Blade-element momentum theory gives a small fixed-pitch rotor (hover inflow ratio ~0.06) a
  // thrust loss of 5-10 % per m/s of climb at fixed speed. 0.25 allows well beyond that and still
  // leaves half the thrust at the autopilot's 2 m/s climb limit, where 0.5 would leave none.
  requireWithinIfOn(climb_inflow_per_m_s, "climb_inflow.per_m_s", 0.0, 0.25, " per m/s");
  requireWithinIfOn(esc_offset_us, "esc_offset.us", -200.0, 200.0, " us");
}

SimEffects SimEffects::onTheBench() const {
  SimEffects bench;
  bench.supply_resistance_ohm = supply_resistance_ohm;
  bench.air = air;
  bench.motor_thermal_resistance_c_per_w = motor_thermal_resistance_c_per_w;
  return bench;
}

std::string SimEffects::summary() const {
  std::string text;
  const auto add = [&text](const std::string& effect) { text += (text.empty() ? "" : " ") + effect; };
  if (supply_resistance_ohm) add("supply_resistance(ohm=" + formatNumber(*supply_resistance_ohm) + ")");
  if (air) {
    add("air_density(temperature_c=" + formatNumber(air->temperature_c) +
        ",pressure_pa=" + formatNumber(air->pressure_pa) + ")");
  }
  if (ground_effect_strength) add("ground_effect(strength=" + formatNumber(*ground_effect_strength) + ")");
  if (thrust_loss_fraction) add("thrust_loss(fraction=" + formatNumber(*thrust_loss_fraction) + ")");
  if (motor_thermal_resistance_c_per_w) {
    add("motor_temperature(thermal_resistance_c_per_w=" + formatNumber(*motor_thermal_resistance_c_per_w) + ")");
  }
  if (climb_inflow_per_m_s) add("climb_inflow(per_m_s=" + formatNumber(*climb_inflow_per_m_s) + ")");
  if (esc_offset_us) add("esc_offset(us=" + formatNumber(*esc_offset_us) + ")");
  return text.empty() ? "none" : text;
}

double groundEffectFactor(double rotor_radius_m, double rotor_height_m, double strength) {
  const double z = std::max(rotor_height_m, 0.5 * rotor_radius_m);
  const double ratio = rotor_radius_m / (4.0 * z);
  return 1.0 + strength * (1.0 / (1.0 - ratio * ratio) - 1.0);
}

RotorEffectTerms rotorEffectTerms(const SimEffects& effects, double rotor_radius_m, double rotor_height_m,
                                  double climb_rate_m_s) {
  RotorEffectTerms terms;
  if (effects.ground_effect_strength) {
    terms.ground_effect = groundEffectFactor(rotor_radius_m, rotor_height_m, *effects.ground_effect_strength);
  }
  if (effects.climb_inflow_per_m_s) terms.climb = std::max(0.0, 1.0 - *effects.climb_inflow_per_m_s * climb_rate_m_s);
  if (effects.thrust_loss_fraction) terms.thrust_loss = 1.0 - *effects.thrust_loss_fraction;
  return terms;
}

}  // namespace propulsion_estimator
