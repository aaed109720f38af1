#include "propulsion_estimator/sim/flight/esc_telemetry_sensor.h"

#include <cmath>

#include "propulsion_estimator/sim/physics/gaussian_noise.h"

namespace propulsion_estimator {
namespace sim {
namespace {

// DShot/BLHeli_32 telemetry carries the electrical rpm in steps of 100; MAVLink carries 0.01 A and
// 0.01 V.
constexpr double kErpmStep = 100.0;
constexpr double kMavlinkStep = 0.01;

double quantised(double value, double step) { return std::round(value / step) * step; }

}  // namespace

EscTelemetrySensor::EscTelemetrySensor(const FlightSensorParams& sensors, int motors, bool px4, std::uint64_t seed)
    : sensors_(sensors), rng_(seed) {
  for (int k = 0; k < motors; ++k) {
    current_gain_.push_back(1.0 + noise(sensors.esc_current_gain_sigma));
    current_offset_a_.push_back(noise(sensors.esc_current_offset_sigma_a));
    voltage_gain_.push_back(1.0 + noise(sensors.esc_voltage_gain_sigma));
  }
  sample_.px4 = px4;
  sample_.escs.resize(motors);
}

double EscTelemetrySensor::noise(double sigma) { return gaussianNoise(sigma, rng_); }

bool EscTelemetrySensor::lost() {
  return std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < sensors_.esc_dropout_probability;
}

const EscTelemetrySample& EscTelemetrySensor::read(double time_s, const PowerTrainState& power) {
  sample_.time_s = time_s;
  const double rpm_step = kErpmStep / sensors_.esc_pole_pairs;
  for (std::size_t k = 0; k < sample_.escs.size(); ++k) {
    // Every draw is made whether or not the packet is lost, so that one loss leaves the others alone.
    const double rpm = quantised(std::max(0.0, power.motors[k].rpm() + noise(sensors_.esc_rpm_sigma)), rpm_step);
    const double current = quantised(
        std::max(0.0, current_gain_[k] * power.motors[k].input_current_a + current_offset_a_[k] +
                          noise(sensors_.esc_current_sigma_a)),
        kMavlinkStep);
    const double voltage =
        quantised(voltage_gain_[k] * power.esc_voltage_v + noise(sensors_.esc_voltage_sigma_v), kMavlinkStep);
    if (lost()) continue;
    EscReading& reading = sample_.escs[k];
    reading.rpm = rpm;
    reading.current_a = current;
    reading.voltage_v = voltage;
    // The winding's temperature stands in for the ESC's own, in whole degrees as ESCs report it.
    reading.temperature_c = std::round(power.winding_temperature_c[k]);
    ++reading.count;
  }
  return sample_;
}

}  // namespace sim
}  // namespace propulsion_estimator
