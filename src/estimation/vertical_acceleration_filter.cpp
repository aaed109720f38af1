#include "propulsion_estimator/estimation/vertical_acceleration_filter.h"

#include <algorithm>

namespace propulsion_estimator {

VerticalAccelerationFilter::VerticalAccelerationFilter(double fast_time_constant_s, double bias_time_constant_s)
    : fast_tau_s_(fast_time_constant_s), slow_tau_s_(bias_time_constant_s) {}

double VerticalAccelerationFilter::add(double stamp_s, double accel_m_s2) {
  if (!started_) {
    // Start with the bias estimate at the first reading: on the ground it is the bias itself.
    fast_ = slow_ = accel_m_s2;
    started_ = true;
  } else {
    const double dt = std::max(stamp_s - last_stamp_s_, 0.0);
    fast_ += dt / (fast_tau_s_ + dt) * (accel_m_s2 - fast_);
    const double bias_dt = std::min(dt, kMaxBiasStepS);
    slow_ += bias_dt / (slow_tau_s_ + bias_dt) * (accel_m_s2 - slow_);
  }
  last_stamp_s_ = stamp_s;
  return value();
}

}  // namespace propulsion_estimator
