#include "propulsion_estimator/sim/physics/sim_effects_yaml.h"

#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/sim/physics/atmosphere_yaml.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {
namespace sim {
namespace {

// The single parameter of an effect.
double parameter(const YamlMap& root, const char* effect, const char* name) {
  const YamlMap map = root.map(effect);
  map.allowOnly({name});
  return map.number(name);
}

}  // namespace

SimEffects parseSimEffectsYaml(const std::string& text, const std::string& source) {
  const YamlMap root = parseYamlDocument(text, source);
  root.allowOnly({"supply_resistance", "air_density", "ground_effect", "thrust_loss", "motor_temperature",
                  "climb_inflow", "esc_offset", "translational_lift"});
  SimEffects effects;
  // Keys, not has(): an effect written without its parameter is refused, not silently off.
  for (const std::string& effect : root.keys()) {
    if (effect == "supply_resistance") {
      const YamlMap map = root.map("supply_resistance");
      map.allowOnly({"ohm", "current_coefficient_per_a"});
      effects.supply_resistance_ohm = map.number("ohm");
      effects.supply_current_coefficient_per_a = map.optionalNumber("current_coefficient_per_a").value_or(0.0);
    }
    if (effect == "air_density") effects.air = readAirConditions(root.map("air_density"));
    if (effect == "ground_effect") effects.ground_effect_strength = parameter(root, "ground_effect", "strength");
    if (effect == "thrust_loss") {
      const YamlMap map = root.map("thrust_loss");
      map.allowOnly({"fraction", "load_exponent", "reference_thrust_n"});
      effects.thrust_loss_fraction = map.number("fraction");
      // A loss that follows the loading needs the loading it is `fraction` at: both or neither.
      if (map.has("load_exponent") || map.has("reference_thrust_n")) {
        effects.thrust_loss_load_exponent = map.number("load_exponent");
        effects.thrust_loss_reference_thrust_n = map.number("reference_thrust_n");
      }
    }
    if (effect == "motor_temperature") {
      effects.motor_thermal_resistance_c_per_w = parameter(root, "motor_temperature", "thermal_resistance_c_per_w");
    }
    if (effect == "climb_inflow") effects.climb_inflow_strength = parameter(root, "climb_inflow", "strength");
    if (effect == "esc_offset") {
      const YamlMap map = root.map("esc_offset");
      map.allowOnly({"us", "per_esc_us", "gain", "dead_band_us"});
      effects.esc_offset_us = map.number("us");
      if (map.has("per_esc_us")) effects.esc_offset_per_esc_us = map.numbers("per_esc_us");
      effects.esc_gain = map.optionalNumber("gain").value_or(1.0);
      effects.esc_dead_band_us = map.optionalNumber("dead_band_us").value_or(0.0);
    }
    if (effect == "translational_lift") {
      effects.translational_lift_strength = parameter(root, "translational_lift", "strength");
    }
  }
  validateAt(root, effects);
  return effects;
}

SimEffects loadSimEffectsFile(const std::string& path) { return parseSimEffectsYaml(readTextFile(path), path); }

}  // namespace sim
}  // namespace propulsion_estimator
