#pragma once

#include <random>

namespace propulsion_estimator {
namespace sim {

/// One sensor of a thrust stand: additive Gaussian noise, then quantisation to its resolution
/// (0: none). The reading's scatter about the truth is effectiveSigma().
struct SensorNoise {
  double sigma = 0.0;  ///< standard deviation of the additive noise, in the sensor's unit
  double resolution = 0.0;  ///< quantisation step, in the sensor's unit; 0: none

  /// A reading of `true_value`: noise drawn from `rng`, then quantised.
  double measure(double true_value, std::mt19937_64& rng) const;
  /// sqrt(sigma^2 + resolution^2 / 12): noise plus uniform quantisation error.
  double effectiveSigma() const;
};

/// The thesis bench's sensors (chapter 3), in SI units.
struct BenchSensors {
  SensorNoise thrust_n;       ///< load cell + HX711
  SensorNoise current_a;      ///< ACS712-30A on the Arduino's 10-bit ADC
  SensorNoise voltage_v;      ///< B25 divider on the Arduino's 10-bit ADC
  SensorNoise rpm;            ///< optical tachometer
  SensorNoise temperature_c;  ///< MLX90615 infrared thermometer (motor and room)

  /// Throws FieldError (`bench.sensors.<sensor>`) for a negative or absurd sigma or resolution.
  void validate() const;
};

}  // namespace sim
}  // namespace propulsion_estimator
