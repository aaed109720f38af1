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
    if (effect == "supply_resistance") effects.supply_resistance_ohm = parameter(root, "supply_resistance", "ohm");
    if (effect == "air_density") effects.air = readAirConditions(root.map("air_density"));
    if (effect == "ground_effect") effects.ground_effect_strength = parameter(root, "ground_effect", "strength");
    if (effect == "thrust_loss") effects.thrust_loss_fraction = parameter(root, "thrust_loss", "fraction");
    if (effect == "motor_temperature") {
      effects.motor_thermal_resistance_c_per_w = parameter(root, "motor_temperature", "thermal_resistance_c_per_w");
    }
    if (effect == "climb_inflow") effects.climb_inflow_strength = parameter(root, "climb_inflow", "strength");
    if (effect == "esc_offset") effects.esc_offset_us = parameter(root, "esc_offset", "us");
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
