#include "propulsion_estimator/sim/physics/atmosphere.h"

#include <cmath>
#include <string>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {

double AirConditions::densityKgM3() const {
  return pressure_pa / (kSpecificGasConstantDryAir * (temperature_c + kZeroCelsiusInKelvin));
}

double AirConditions::pressureAtHeightPa(double height_m) const {
  return pressure_pa *
         std::exp(-kStandardGravity * height_m / (kSpecificGasConstantDryAir * (temperature_c + kZeroCelsiusInKelvin)));
}

void AirConditions::validate(const char* field) const {
  const std::string prefix = field;
  if (!(temperature_c >= -40.0 && temperature_c <= 60.0)) {
    throw FieldError(prefix + ".temperature_c", formatNumber(temperature_c) + " is outside -40..60 deg C");
  }
  if (!(pressure_pa >= 50000.0 && pressure_pa <= 110000.0)) {
    throw FieldError(prefix + ".pressure_pa", formatNumber(pressure_pa) + " is outside 50000..110000 Pa");
  }
}

}  // namespace propulsion_estimator
