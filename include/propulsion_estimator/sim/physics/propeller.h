#pragma once

#include <string>

namespace propulsion_estimator {

// Fixed-pitch propeller in static (hover) conditions with constant coefficients, n in rev/s:
// T = CT rho n^2 D^4, Q = CQ rho n^2 D^5.
struct PropellerParams {
  std::string name;
  double diameter_m = 0.0;
  double thrust_coefficient = 0.0;  // CT
  double torque_coefficient = 0.0;  // CQ (power coefficient CP = 2 pi CQ)
  double inertia_kg_m2 = 0.0;

  // Throws FieldError (propeller.*) for a value outside its physical range.
  void validate() const;

  double radiusM() const { return 0.5 * diameter_m; }
  double thrustN(double air_density_kg_m3, double rev_per_s) const;
  double torqueNm(double air_density_kg_m3, double rev_per_s) const;
};

}  // namespace propulsion_estimator
