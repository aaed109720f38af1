#include "propulsion_estimator/sim/physics/bench_sensors.h"

#include <cmath>
#include <string>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/sim/physics/gaussian_noise.h"

namespace propulsion_estimator {
namespace sim {
namespace {

// Field names as the parameter file spells them: bench.sensors.<name>.sigma_<unit>.
void validateSensor(const SensorNoise& sensor, const std::string& name, const std::string& unit, double limit) {
  const std::string field = "bench.sensors." + name + ".";
  requireWithin(field + "sigma_" + unit, sensor.sigma, 0.0, limit);
  requireWithin(field + "resolution_" + unit, sensor.resolution, 0.0, limit);
}

}  // namespace

double SensorNoise::measure(double true_value, std::mt19937_64& rng) const {
  double value = true_value + gaussianNoise(sigma, rng);
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

}  // namespace sim
}  // namespace propulsion_estimator
