#include "propulsion_estimator/sim/physics/atmosphere_yaml.h"

namespace propulsion_estimator {
namespace sim {

AirConditions readAirConditions(const YamlMap& map) {
  map.allowOnly({"temperature_c", "pressure_pa"});
  return AirConditions{map.number("temperature_c"), map.number("pressure_pa")};
}

}  // namespace sim
}  // namespace propulsion_estimator
