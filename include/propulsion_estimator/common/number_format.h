#pragma once

#include <string>

namespace propulsion_estimator {

// Shortest decimal form of `value` that reads back to the same double ("0.1", "1e-05", "1315"):
// for files that must round-trip and for messages that quote a value.
std::string formatNumber(double value);

// `value` formatted with one printf conversion ("%.2f", "%.4g"): for reports and messages.
std::string formatPrintf(const char* pattern, double value);

}  // namespace propulsion_estimator
