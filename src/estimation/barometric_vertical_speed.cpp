#include "propulsion_estimator/estimation/barometric_vertical_speed.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace {

constexpr double kStandardTemperatureK = 288.15;

}  // namespace

void BarometricVerticalSpeed::add(double stamp_s, double pressure_pa) {
  if (!started_) {
    started_ = true;
    first_stamp_s_ = last_stamp_s_ = stamp_s;
    reference_pa_ = pressure_pa;
    fast_m_ = slow_m_ = 0.0;
    return;
  }
  const double height_m = kSpecificGasConstantDryAir * kStandardTemperatureK / kStandardGravity *
                          std::log(reference_pa_ / pressure_pa);
  const double dt = std::max(stamp_s - last_stamp_s_, 0.0);
  fast_m_ += (1.0 - std::exp(-dt / kFastTimeConstantS)) * (height_m - fast_m_);
  slow_m_ += (1.0 - std::exp(-dt / kSlowTimeConstantS)) * (height_m - slow_m_);
  last_stamp_s_ = stamp_s;
}

double BarometricVerticalSpeed::value() const {
  if (!started_ || last_stamp_s_ - first_stamp_s_ < kSettlingS) return kNaN;
  return (fast_m_ - slow_m_) / (kSlowTimeConstantS - kFastTimeConstantS);
}

}  // namespace propulsion_estimator
