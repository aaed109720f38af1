#pragma once

#include "propulsion_estimator/common/not_a_number.h"

namespace propulsion_estimator {

/// A rotor's thrust against its speed as ESC telemetry measures it, fitted on a bench log's rpm
/// column: T = (a n^2 + b n) rho / rho_bench, n in rpm. At a given speed the thrust does not depend
/// on the ESC's end points, the supply's resistance or the battery's sag, which move the PWM
/// surfaces; it scales with the air's density (momentum theory, a propeller at fixed speed).
struct RpmThrust {
  double n_per_rpm2 = 0.0;  ///< a, N/rpm^2
  double n_per_rpm = 0.0;   ///< b, N/rpm
  double bench_air_density_kg_m3 = kNaN;  ///< rho_bench, kg/m^3; NaN: no density correction
  double rms_n = kNaN;  ///< N, the fit's residual
  int rows = 0;  ///< bench rows it was fitted on

  /// Thrust in N at `rpm` in air of `air_density_kg_m3` (NaN: the bench's); 0 at or below 0 rpm.
  double thrustN(double rpm, double air_density_kg_m3 = kNaN) const;
};

}  // namespace propulsion_estimator
