#pragma once

#include "propulsion_estimator/sim/physics/atmosphere.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {
namespace sim {

/// Air written as {temperature_c, pressure_pa}, both required, nothing else: the bench air of a
/// simulator parameter file and the air_density effect. Ranges are checked by AirConditions::validate.
AirConditions readAirConditions(const YamlMap& map);

}  // namespace sim
}  // namespace propulsion_estimator
