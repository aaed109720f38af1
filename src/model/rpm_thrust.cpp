#include "propulsion_estimator/model/rpm_thrust.h"

#include <cmath>

namespace propulsion_estimator {

double RpmThrust::thrustN(double rpm, double air_density_kg_m3) const {
  if (!(rpm > 0.0)) return 0.0;
  const double ratio = std::isnan(air_density_kg_m3) || std::isnan(bench_air_density_kg_m3)
                           ? 1.0
                           : air_density_kg_m3 / bench_air_density_kg_m3;
  return (n_per_rpm2 * rpm * rpm + n_per_rpm * rpm) * ratio;
}

}  // namespace propulsion_estimator
