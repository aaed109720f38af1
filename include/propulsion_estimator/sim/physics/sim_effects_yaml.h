#pragma once

#include <string>

#include "propulsion_estimator/sim/physics/sim_effects.h"

namespace propulsion_estimator {
namespace sim {

/// Reader of an effects file: a mapping whose keys switch effects on, each with its parameter:
///   supply_resistance: {ohm: 0.05}
///   air_density: {temperature_c: 35, pressure_pa: 90000}
///   ground_effect: {strength: 1.0}
///   thrust_loss: {fraction: 0.05}
///   motor_temperature: {thermal_resistance_c_per_w: 2.0}
///   climb_inflow: {strength: 1.0}
///   esc_offset: {us: 20}
/// `{}` is the file of no effects. Unknown effects or parameters, missing parameters and values
/// out of range are refused with ConfigError "<file>:<line>: <key>: <problem>".
SimEffects parseSimEffectsYaml(const std::string& text, const std::string& source);
/// Reads and parses the effects file `path`; InputError when it cannot be read.
SimEffects loadSimEffectsFile(const std::string& path);

}  // namespace sim
}  // namespace propulsion_estimator
