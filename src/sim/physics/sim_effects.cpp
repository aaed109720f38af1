#include "propulsion_estimator/sim/physics/sim_effects.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace sim {
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
  // Strength 1 gives the thesis quad's rotors -4.8 % of thrust per m/s of climb at fixed speed;
  // 3 (-14 % per m/s) still leaves the autopilot's 2 m/s climb about two thirds of the thrust.
  requireWithinIfOn(climb_inflow_strength, "climb_inflow.strength", 0.0, 3.0, "");
  requireWithinIfOn(esc_offset_us, "esc_offset.us", -200.0, 200.0, " us");
  requireWithinIfOn(translational_lift_strength, "translational_lift.strength", 0.0, 2.0, "");
  requireWithin("supply_resistance.current_coefficient_per_a", supply_current_coefficient_per_a, 0.0, 0.1, " 1/A");
  requireWithin("thrust_loss.load_exponent", thrust_loss_load_exponent, -2.0, 2.0, "");
  requireWithin("thrust_loss.reference_thrust_n", thrust_loss_reference_thrust_n, 0.01, 1000.0, " N");
  for (double us : esc_offset_per_esc_us) requireWithin("esc_offset.per_esc_us", us, -100.0, 100.0, " us");
  requireWithin("esc_offset.gain", esc_gain, 0.8, 1.2, "");
  requireWithin("esc_offset.dead_band_us", esc_dead_band_us, 0.0, 50.0, " us");
}

void SimEffects::validateEscCount(int escs) const {
  if (!esc_offset_us || esc_offset_per_esc_us.empty() || static_cast<int>(esc_offset_per_esc_us.size()) == escs) {
    return;
  }
  throw FieldError("esc_offset.per_esc_us", "has " + std::to_string(esc_offset_per_esc_us.size()) +
                                                " entries for the vehicle's " + std::to_string(escs) + " rotors");
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
  if (supply_resistance_ohm) {
    add("supply_resistance(ohm=" + formatNumber(*supply_resistance_ohm) +
        (supply_current_coefficient_per_a != 0.0
             ? ",current_coefficient_per_a=" + formatNumber(supply_current_coefficient_per_a)
             : std::string()) +
        ")");
  }
  if (air) {
    add("air_density(temperature_c=" + formatNumber(air->temperature_c) +
        ",pressure_pa=" + formatNumber(air->pressure_pa) + ")");
  }
  if (ground_effect_strength) add("ground_effect(strength=" + formatNumber(*ground_effect_strength) + ")");
  if (thrust_loss_fraction) {
    add("thrust_loss(fraction=" + formatNumber(*thrust_loss_fraction) +
        (thrust_loss_load_exponent != 0.0 ? ",load_exponent=" + formatNumber(thrust_loss_load_exponent) +
                                                ",reference_thrust_n=" + formatNumber(thrust_loss_reference_thrust_n)
                                          : std::string()) +
        ")");
  }
  if (motor_thermal_resistance_c_per_w) {
    add("motor_temperature(thermal_resistance_c_per_w=" + formatNumber(*motor_thermal_resistance_c_per_w) + ")");
  }
  if (climb_inflow_strength) add("climb_inflow(strength=" + formatNumber(*climb_inflow_strength) + ")");
  if (esc_offset_us) {
    std::string form;
    for (std::size_t k = 0; k < esc_offset_per_esc_us.size(); ++k) {
      form += (k == 0 ? ",per_esc_us=[" : ";") + formatNumber(esc_offset_per_esc_us[k]);
    }
    if (!form.empty()) form += "]";
    if (esc_gain != 1.0) form += ",gain=" + formatNumber(esc_gain);
    if (esc_dead_band_us != 0.0) form += ",dead_band_us=" + formatNumber(esc_dead_band_us);
    add("esc_offset(us=" + formatNumber(*esc_offset_us) + form + ")");
  }
  if (translational_lift_strength) {
    add("translational_lift(strength=" + formatNumber(*translational_lift_strength) + ")");
  }
  return text.empty() ? "none" : text;
}

double airframeThrustShare(const SimEffects& effects, double rotor_thrust_n) {
  if (!effects.thrust_loss_fraction) return 1.0;
  double loss = *effects.thrust_loss_fraction;
  if (effects.thrust_loss_load_exponent != 0.0) {
    loss *= std::pow(std::max(rotor_thrust_n, 0.0) / effects.thrust_loss_reference_thrust_n,
                     effects.thrust_loss_load_exponent);
  }
  return std::max(0.0, 1.0 - loss);
}

double escDuty(const SimEffects& effects, const EscParams& params, int esc, double pulse_us) {
  double offset = effects.esc_offset_us.value_or(0.0);
  if (effects.esc_offset_us && !effects.esc_offset_per_esc_us.empty()) {
    if (esc < 0 || esc >= static_cast<int>(effects.esc_offset_per_esc_us.size())) {
      throw FieldError("esc_offset.per_esc_us", "has " + std::to_string(effects.esc_offset_per_esc_us.size()) +
                                                    " entries, no entry for ESC " + std::to_string(esc + 1));
    }
    offset += effects.esc_offset_per_esc_us[esc];
  }
  if (!effects.esc_offset_us || (effects.esc_gain == 1.0 && effects.esc_dead_band_us == 0.0)) {
    return params.duty(pulse_us, offset);
  }
  const double above = pulse_us - params.pwm_zero_us - offset;
  if (above <= effects.esc_dead_band_us) return 0.0;
  return std::clamp(effects.esc_gain * above / (params.pwm_full_us - params.pwm_zero_us), 0.0, 1.0);
}

double groundEffectFactor(double rotor_radius_m, double rotor_height_m, double strength) {
  const double z = std::max(rotor_height_m, 0.5 * rotor_radius_m);
  const double ratio = rotor_radius_m / (4.0 * z);
  return 1.0 + strength * (1.0 / (1.0 - ratio * ratio) - 1.0);
}

RotorInflow rotorInflow(const SimEffects& effects, double rotor_radius_m, double rotor_height_m,
                        double axial_speed_m_s, double edgewise_speed_m_s) {
  RotorInflow inflow;
  if (effects.ground_effect_strength) {
    inflow.ground_inflow_ratio =
        1.0 / groundEffectFactor(rotor_radius_m, rotor_height_m, *effects.ground_effect_strength);
  }
  if (effects.climb_inflow_strength) inflow.axial_speed_m_s = *effects.climb_inflow_strength * axial_speed_m_s;
  if (effects.translational_lift_strength) {
    inflow.edgewise_speed_m_s = *effects.translational_lift_strength * edgewise_speed_m_s;
  }
  return inflow;
}

}  // namespace sim
}  // namespace propulsion_estimator
