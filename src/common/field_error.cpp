#include "propulsion_estimator/common/field_error.h"

#include <cmath>

#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {

void requireWithin(const std::string& field, double value, double lo, double hi, const std::string& unit) {
  if (!(value >= lo && value <= hi)) {
    throw FieldError(field, formatNumber(value) + " is outside " + formatNumber(lo) + ".." + formatNumber(hi) + unit);
  }
}

void requirePositive(const std::string& field, double value, double hi, const std::string& unit) {
  if (std::isinf(hi)) {
    if (!(value > 0.0 && value < hi)) throw FieldError(field, "must be a positive number, got " + formatNumber(value));
    return;
  }
  if (!(value > 0.0 && value <= hi)) {
    throw FieldError(field, formatNumber(value) + " is outside 0.." + formatNumber(hi) + unit + " (must be positive)");
  }
}

}  // namespace propulsion_estimator
