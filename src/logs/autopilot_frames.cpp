#include "propulsion_estimator/logs/autopilot_frames.h"

#include <cmath>

namespace propulsion_estimator {

Eigen::Quaterniond swapNedEnuFrdFlu(const Eigen::Quaterniond& attitude) {
  // ENU<->NED swaps x and y and negates z; FLU<->FRD negates y and z: both are half-turns.
  static const Eigen::Quaterniond kEnuNed(0.0, M_SQRT1_2, M_SQRT1_2, 0.0);
  static const Eigen::Quaterniond kFrdFlu(0.0, 1.0, 0.0, 0.0);
  return kEnuNed * attitude * kFrdFlu;
}

const Eigen::Vector3d* LatestSpecificForce::at(double time_s) {
  while (next_ < forces_.size() && forces_[next_].first <= time_s) ++next_;
  if (next_ == 0 || time_s - forces_[next_ - 1].first > 0.1) return nullptr;  // no fresh specific force
  return &forces_[next_ - 1].second;
}

}  // namespace propulsion_estimator
