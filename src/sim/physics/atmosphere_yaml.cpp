#include "propulsion_estimator/sim/physics/atmosphere_yaml.h"

namespace propulsion_estimator {

AirConditions readAirConditions(const YamlMap& map) {
  map.allowOnly({"temperature_c", "pressure_pa"});
  return AirConditions{map.number("temperature_c"), map.number("pressure_pa")};
}

}  // namespace propulsion_estimator
