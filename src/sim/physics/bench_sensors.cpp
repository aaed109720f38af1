#include "propulsion_estimator/sim/physics/bench_sensors.h"

#include <cmath>
#include <string>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace {

// Field names as the parameter file spells them: bench.sensors.<name>.sigma_<unit>.
void validateSensor(const SensorNoise& sensor, const std::string& name, const std::string& unit, double limit) {
  const std::string field = "bench.sensors." + name + ".";
  if (!(sensor.sigma >= 0.0 && sensor.sigma <= limit)) {
    throw FieldError(field + "sigma_" + unit, formatNumber(sensor.sigma) + " is outside 0.." + formatNumber(limit));
  }
  if (!(sensor.resolution >= 0.0 && sensor.resolution <= limit)) {
    throw FieldError(field + "resolution_" + unit,
                     formatNumber(sensor.resolution) + " is outside 0.." + formatNumber(limit));
  }
}

}  // namespace

double SensorNoise::measure(double true_value, std::mt19937_64& rng) const {
  double value = true_value;
  if (sigma > 0.0) value += std::normal_distribution<double>(0.0, sigma)(rng);
  if (resolution > 0.0) value = resolution * std::round(value / resolution);
  return value;
}

double SensorNoise::effectiveSigma() const { return std::sqrt(sigma * sigma + resolution * resolution / 12.0); }

void BenchSensors::validate() const {
  validateSensor(thrust_n, "load_cell", "n", 10.0);
  validateSensor(current_a, "current", "a", 10.0);
  validateSensor(voltage_v, "voltage", "v", 1.0);
  validateSensor(rpm, "rpm", "rpm", 1000.0);
  validateSensor(temperature_c, "temperature", "c", 10.0);
}

}  // namespace propulsion_estimator
