#include "propulsion_estimator/sim/physics/propeller.h"

#include "propulsion_estimator/common/field_error.h"

namespace propulsion_estimator {

void PropellerParams::validate() const {
  requireWithin("propeller.diameter_m", diameter_m, 0.02, 2.0);
  requireWithin("propeller.thrust_coefficient", thrust_coefficient, 0.001, 0.5);
  requireWithin("propeller.torque_coefficient", torque_coefficient, 0.0001, 0.1);
  requireWithin("propeller.inertia_kg_m2", inertia_kg_m2, 0.0, 0.1);
}

double PropellerParams::thrustN(double air_density_kg_m3, double rev_per_s) const {
  const double d2 = diameter_m * diameter_m;
  return thrust_coefficient * air_density_kg_m3 * rev_per_s * rev_per_s * d2 * d2;
}

double PropellerParams::torqueNm(double air_density_kg_m3, double rev_per_s) const {
  const double d2 = diameter_m * diameter_m;
  return torque_coefficient * air_density_kg_m3 * rev_per_s * rev_per_s * d2 * d2 * diameter_m;
}

}  // namespace propulsion_estimator
