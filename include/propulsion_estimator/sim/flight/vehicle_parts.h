#pragma once

#include <cstdint>
#include <vector>

#include "propulsion_estimator/sim/physics/propulsion_chain.h"

/// @file
/// A vehicle's own parts: real motors, propellers and ESCs differ from part to part, and clockwise
/// and counter-clockwise propellers are not mirror images. A flight profile's `vehicle.parts`
/// section draws each motor's parts from the vehicle's seed, so that every flight of the same
/// vehicle flies the same parts.
namespace propulsion_estimator {
namespace sim {

/// How a vehicle's parts scatter around the parameter file's chain (`vehicle.parts` in a flight
/// profile). Each spread is the standard deviation of a zero-mean Gaussian draw, clipped at
/// kPartSpreadClipSigma (parts beyond it would fail a manufacturer's inspection).
struct VehicleParts {
  /// The vehicle's identity, 0..10^9: the same seed draws the same parts on every flight
  /// (unlike the flight's noise seed).
  std::uint64_t seed = 0;
  double thrust_coefficient_spread = 0.0;  ///< relative, 0..0.1: each propeller's CT x (1 + spread n)
  double torque_coefficient_spread = 0.0;  ///< relative, 0..0.1: each propeller's CQ, drawn apart from CT
  double kv_spread = 0.0;                  ///< relative, 0..0.1: each motor's Kv
  double esc_end_point_spread_us = 0.0;    ///< us, 0..30: both end points of each ESC move by the same shift
  /// 0.8..1.25: the clockwise propellers' torque per thrust (CQ / CT) over the counter-clockwise
  /// ones' (CQ x sqrt(ratio) on clockwise, / sqrt(ratio) on counter-clockwise); 1 for mirror images.
  double spin_torque_ratio = 1.0;

  /// Throws FieldError naming the key (vehicle.parts.kv_spread, ...) for a value outside its range.
  void validate() const;
};

/// Draws beyond this many standard deviations are clipped to it.
constexpr double kPartSpreadClipSigma = 2.0;

/// One motor's drawn parts, as factors of the parameter file's values.
struct MotorParts {
  double thrust_coefficient_factor = 1.0;  ///< x the propeller's CT
  double torque_coefficient_factor = 1.0;  ///< x the propeller's CQ, the spin direction's share included
  double kv_factor = 1.0;                  ///< x the motor's Kv
  double esc_end_point_shift_us = 0.0;     ///< us, added to both of the ESC's end points
};

/// Each motor's parts, in motor order, for motors spinning `spin_directions` (+1 counter-clockwise
/// seen from above, -1 clockwise). Per motor, four standard normal draws in this order: CT, CQ,
/// Kv, ESC shift, always drawn (a spread of 0 leaves the other parts as drawn), from a
/// std::mt19937_64 seeded with parts.seed. Spreads of 0 and a ratio of 1 give factors of exactly 1
/// and shifts of exactly 0. Expects validated parts.
std::vector<MotorParts> drawMotorParts(const VehicleParts& parts, const std::vector<int>& spin_directions);

/// `chain` built with `motor`'s parts (not validated: PropulsionChain validates it).
ChainParams withParts(const ChainParams& chain, const MotorParts& motor);

}  // namespace sim
}  // namespace propulsion_estimator
