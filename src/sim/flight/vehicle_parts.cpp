#include "propulsion_estimator/sim/flight/vehicle_parts.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/sim/physics/gaussian_noise.h"

namespace propulsion_estimator {
namespace sim {
namespace {

constexpr std::uint64_t kLargestSeed = 1000000000;  // the largest integer a profile's YAML reader takes

}  // namespace

void VehicleParts::validate() const {
  if (seed > kLargestSeed) {
    throw FieldError("vehicle.parts.seed", std::to_string(seed) + " is outside 0..1000000000");
  }
  // Beyond 10 % a part would be a different part, not a tolerance.
  requireWithin("vehicle.parts.thrust_coefficient_spread", thrust_coefficient_spread, 0.0, 0.1);
  requireWithin("vehicle.parts.torque_coefficient_spread", torque_coefficient_spread, 0.0, 0.1);
  requireWithin("vehicle.parts.kv_spread", kv_spread, 0.0, 0.1);
  requireWithin("vehicle.parts.esc_end_point_spread_us", esc_end_point_spread_us, 0.0, 30.0, " us");
  requireWithin("vehicle.parts.spin_torque_ratio", spin_torque_ratio, 0.8, 1.25);
}

std::vector<MotorParts> drawMotorParts(const VehicleParts& parts, const std::vector<int>& spin_directions) {
  std::mt19937_64 rng(parts.seed);
  const auto draw = [&rng] { return std::clamp(gaussianNoise(1.0, rng), -kPartSpreadClipSigma, kPartSpreadClipSigma); };
  const double spin_share = std::sqrt(parts.spin_torque_ratio);
  std::vector<MotorParts> motors;
  for (const int spin : spin_directions) {
    MotorParts motor;
    motor.thrust_coefficient_factor = 1.0 + parts.thrust_coefficient_spread * draw();
    motor.torque_coefficient_factor =
        (1.0 + parts.torque_coefficient_spread * draw()) * (spin < 0 ? spin_share : 1.0 / spin_share);
    motor.kv_factor = 1.0 + parts.kv_spread * draw();
    motor.esc_end_point_shift_us = parts.esc_end_point_spread_us * draw();
    motors.push_back(motor);
  }
  return motors;
}

ChainParams withParts(const ChainParams& chain, const MotorParts& motor) {
  ChainParams parted = chain;
  parted.propeller.thrust_coefficient *= motor.thrust_coefficient_factor;
  parted.propeller.torque_coefficient *= motor.torque_coefficient_factor;
  parted.motor.kv_rpm_per_v *= motor.kv_factor;
  parted.esc.pwm_zero_us += motor.esc_end_point_shift_us;
  parted.esc.pwm_full_us += motor.esc_end_point_shift_us;
  return parted;
}

}  // namespace sim
}  // namespace propulsion_estimator
