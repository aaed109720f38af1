#pragma once

#include <limits>

namespace propulsion_estimator {

/// The value of a quantity that is not measured, not modelled or not defined (no IMU, a model
/// without rpm, a ratio over nothing); tested with std::isnan.
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace propulsion_estimator
