#pragma once

namespace propulsion_estimator {

/// Standard gravity, m/s^2; thrust stands report gram-force, so 1 g of "thrust" is 9.80665e-3 N.
constexpr double kStandardGravity = 9.80665;
constexpr double kNewtonPerGramForce = kStandardGravity / 1000.0;   ///< N per gram-force
constexpr double kTwoPi = 2.0 * 3.14159265358979323846;             ///< rad per revolution
constexpr double kRadPerSecPerRpm = 3.14159265358979323846 / 30.0;  ///< rad/s per rpm
constexpr double kSpecificGasConstantDryAir = 287.058;              ///< J/(kg K)
constexpr double kZeroCelsiusInKelvin = 273.15;                     ///< K at 0 deg C

}  // namespace propulsion_estimator
