#include "propulsion_estimator/sim/physics/propeller.h"

#include <cmath>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

void PropellerParams::validate() const {
  requireWithin("propeller.diameter_m", diameter_m, 0.02, 2.0);
  requireWithin("propeller.thrust_coefficient", thrust_coefficient, 0.001, 0.5);
  requireWithin("propeller.torque_coefficient", torque_coefficient, 0.0001, 0.1);
  requireWithin("propeller.inertia_kg_m2", inertia_kg_m2, 0.0, 0.1);
  // Two thin blades of a racing propeller to the wide blades of a heavy-lift one.
  requireWithin("propeller.solidity", solidity, 0.02, 0.5);
  // Momentum theory's ideal torque, C_T^1.5 / sqrt(2), times kappa: below it the rotor model
  // would need a negative profile torque.
  const double induced = kInducedPowerFactor * std::pow(rotorThrustCoefficient(), 1.5) / std::sqrt(2.0);
  if (!(rotorTorqueCoefficient() > induced)) {
    throw FieldError("propeller.torque_coefficient",
                     formatNumber(torque_coefficient) + " is below the induced torque of thrust coefficient " +
                         formatNumber(thrust_coefficient) + " (figure of merit " +
                         formatPrintf("%.3g", induced / kInducedPowerFactor / rotorTorqueCoefficient()) +
                         ", at most 1/" + formatNumber(kInducedPowerFactor) + ")");
  }
}

double PropellerParams::thrustN(double air_density_kg_m3, double rev_per_s) const {
  const double d2 = diameter_m * diameter_m;
  return thrust_coefficient * air_density_kg_m3 * rev_per_s * rev_per_s * d2 * d2;
}

double PropellerParams::torqueNm(double air_density_kg_m3, double rev_per_s) const {
  const double d2 = diameter_m * diameter_m;
  return torque_coefficient * air_density_kg_m3 * rev_per_s * rev_per_s * d2 * d2 * diameter_m;
}

double PropellerParams::rotorThrustCoefficient() const { return 4.0 * thrust_coefficient / (kPi * kPi * kPi); }
double PropellerParams::rotorTorqueCoefficient() const { return 8.0 * torque_coefficient / (kPi * kPi * kPi); }

PropellerParams scaledPropeller(const PropellerParams& propeller, double thrust_factor) {
  PropellerParams scaled = propeller;
  scaled.diameter_m *= std::pow(thrust_factor, 0.25);
  scaled.inertia_kg_m2 *= std::pow(thrust_factor, 1.25);
  return scaled;
}

PropellerParams wornPropeller(const PropellerParams& propeller, double thrust_factor) {
  PropellerParams worn = propeller;
  worn.thrust_coefficient *= thrust_factor;
  return worn;
}

}  // namespace sim
}  // namespace propulsion_estimator
