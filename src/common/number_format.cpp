#include "propulsion_estimator/common/number_format.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace propulsion_estimator {

std::string formatNumber(double value) {
  char buffer[40];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

std::string formatPrintf(const char* pattern, double value, const char* missing) {
  if (missing != nullptr && !std::isfinite(value)) return missing;
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), pattern, value);
  return buffer;
}

std::string formatCsvNumber(double value) { return formatPrintf("%.7g", value, ""); }

}  // namespace propulsion_estimator
