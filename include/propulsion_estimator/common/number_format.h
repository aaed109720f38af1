#pragma once

#include <string>

namespace propulsion_estimator {

/// Shortest decimal form of `value` that reads back to the same double ("0.1", "1e-05", "1315"):
/// for files that must round-trip and for messages that quote a value.
std::string formatNumber(double value);

/// `value` formatted with one printf conversion ("%.2f", "%.4g"): for reports and messages. A value
/// that is not finite (not measured, not modelled, not computable) is written as `missing` when one
/// is given ("" in a CSV cell, "n/a" in a table), else as printf writes it ("nan", "inf").
std::string formatPrintf(const char* pattern, double value, const char* missing = nullptr);

/// A number in a CSV cell of a report: 7 significant digits, an empty cell when not finite.
std::string formatCsvNumber(double value);

}  // namespace propulsion_estimator
