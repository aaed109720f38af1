#pragma once

#include <vector>

#include "propulsion_estimator/logs/bench_log.h"
#include "propulsion_estimator/model/rpm_thrust.h"

namespace propulsion_estimator {

/// Least squares of thrust against rpm (T = a n^2 + b n) over the rows of `logs` that have both, a
/// positive rpm and a finite thrust; `bench_air_density_kg_m3` (kg/m^3, NaN when unknown) is the
/// density the result refers to. Throws DataError "<source>: no rpm column" when no log has one,
/// and "... fewer than 10 rows with rpm and thrust" when too few rows have both.
RpmThrust fitRpmThrust(const std::vector<BenchLog>& logs, double bench_air_density_kg_m3);

}  // namespace propulsion_estimator
