#pragma once

#include <Eigen/Core>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/onboard/forgetting_line_fit.h"

namespace propulsion_estimator {

/// The resistance between the battery's terminals and the ESCs (leads, connectors, a power
/// module's shunt) from the voltage it drops against the current through it: recursive least
/// squares with forgetting of drop = offset + R I (the offset takes up the ESCs' and the power
/// module's voltage-divider errors), as autopilots estimate their battery's resistance. O(1) per
/// sample, fixed memory. Each variance is bounded by the prior, so that a long steady hover (no
/// change of current) does not wind the covariance up; the standard deviation says how well the
/// current's changes have identified R.
class SupplyResistanceEstimator {
 public:
  /// `memory_s` > 0: the time constant over which older samples are forgotten, s;
  /// `voltage_sigma_v` > 0: the noise of one drop, V (it scales the prior).
  SupplyResistanceEstimator(double memory_s, double voltage_sigma_v);

  /// One sample at `time_s` (s): the drop from the battery's terminals to the ESCs in V and the
  /// ESCs' summed current in A. Non-finite values, or a time not after the last, are ignored.
  void add(double time_s, double drop_v, double current_a);
  /// Forgets every sample.
  void reset();

  double resistanceOhm() const;  ///< ohm, NaN before two samples
  double resistanceStdOhm() const;  ///< ohm, one standard deviation; NaN before two samples
  int samples() const { return samples_; }  ///< used since the start or reset()

 private:
  double memory_s_;
  double sigma2_;
  double last_time_s_ = kNaN;
  int samples_ = 0;
  double residual2_sum_ = 0.0;  ///< forgetting sum of squared normalised residuals, V^2
  double weight_sum_ = 0.0;  ///< forgetting count of them
  ForgettingLineFit fit_;  ///< drop = offset (V) + R (ohm) x current
};

}  // namespace propulsion_estimator
