#pragma once

#include <string>

namespace propulsion_estimator {
namespace sim {

/// Induced power factor kappa of a hovering rotor: its induced power over momentum theory's ideal
/// (non-uniform inflow, tip loss; J. G. Leishman, Principles of Helicopter Aerodynamics, 2006, ch. 2:
/// 1.15 typical). A propeller's figure of merit cannot exceed 1 / kappa.
constexpr double kInducedPowerFactor = 1.15;

/// Fixed-pitch propeller with constant coefficients measured in static conditions (still air, out
/// of ground effect), n in rev/s: T = CT rho n^2 D^4, Q = CQ rho n^2 D^5. How they change with the
/// inflow (climb, descent, ground) is RotorAerodynamics' (rotor_inflow.h), which needs the solidity.
struct PropellerParams {
  std::string name;  ///< for metadata and messages
  double diameter_m = 0.0;  ///< m
  double thrust_coefficient = 0.0;  ///< CT
  double torque_coefficient = 0.0;  ///< CQ (power coefficient CP = 2 pi CQ)
  double inertia_kg_m2 = 0.0;  ///< kg m^2, about the shaft
  double solidity = 0.0;  ///< blade area over disc area, blades x chord at 3/4 radius / (pi R)

  /// Throws FieldError (propeller.*) for a value outside its physical range, and
  /// propeller.torque_coefficient for a torque below the induced torque of the thrust (figure of
  /// merit above 1 / kInducedPowerFactor).
  void validate() const;

  /// Radius, m.
  double radiusM() const { return 0.5 * diameter_m; }
  /// N, T = CT rho n^2 D^4, in still air out of ground effect
  double thrustN(double air_density_kg_m3, double rev_per_s) const;
  /// N m, Q = CQ rho n^2 D^5, in still air out of ground effect
  double torqueNm(double air_density_kg_m3, double rev_per_s) const;
  /// The rotorcraft coefficients C_T = T / (rho pi R^2 (Omega R)^2) = 4 CT / pi^3 and
  /// C_Q = Q / (rho pi R^2 (Omega R)^2 R) = 8 CQ / pi^3.
  double rotorThrustCoefficient() const;
  double rotorTorqueCoefficient() const;  ///< see rotorThrustCoefficient
};

/// A geometrically similar propeller that makes `thrust_factor` of this one's thrust at the same
/// rotor speed, as a cut-down or damaged one: diameter x f^(1/4) (T ~ D^4), so its torque is
/// x f^(5/4) (Q ~ D^5) and its inertia x f^(5/4) (mass ~ D^3, radius of gyration ~ D). The factor
/// is checked by the caller.
PropellerParams scaledPropeller(const PropellerParams& propeller, double thrust_factor);

/// A worn or bent propeller that makes `thrust_factor` of this one's thrust at the same rotor speed
/// with the same torque: CT x f, CQ, diameter and inertia unchanged. The factor is checked by the
/// caller.
PropellerParams wornPropeller(const PropellerParams& propeller, double thrust_factor);

}  // namespace sim
}  // namespace propulsion_estimator
