#include "propulsion_estimator/sim/physics/atmosphere.h"

#include <cmath>
#include <string>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace sim {

double AirConditions::densityKgM3() const {
  return pressure_pa / (kSpecificGasConstantDryAir * (temperature_c + kZeroCelsiusInKelvin));
}

double AirConditions::pressureAtHeightPa(double height_m) const {
  return pressure_pa *
         std::exp(-kStandardGravity * height_m / (kSpecificGasConstantDryAir * (temperature_c + kZeroCelsiusInKelvin)));
}

void AirConditions::validate(const char* field) const {
  const std::string prefix = field;
  requireWithin(prefix + ".temperature_c", temperature_c, -40.0, 60.0, " deg C");
  requireWithin(prefix + ".pressure_pa", pressure_pa, 50000.0, 110000.0, " Pa");
}

}  // namespace sim
}  // namespace propulsion_estimator
