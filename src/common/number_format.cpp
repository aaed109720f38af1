#include "propulsion_estimator/common/number_format.h"

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

std::string formatPrintf(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), pattern, value);
  return buffer;
}

}  // namespace propulsion_estimator
