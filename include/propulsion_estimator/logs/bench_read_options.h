#pragma once

#include <map>
#include <string>

#include "propulsion_estimator/logs/bench_log.h"
#include "propulsion_estimator/logs/csv_text.h"

namespace propulsion_estimator {

/// How to read a logged quantity whose sign depends on how the stand was mounted (a pusher
/// propeller pulls the load cell the other way; some shunts are wired reversed).
enum class SignPolicy {
  kAuto,      ///< as logged when (nearly) all values are >= 0, negated when (nearly) all are <= 0,
              ///< refused when both signs are substantial
  kAsLogged,  ///< keep the sign
  kNegate,    ///< negate every value
};

/// Choices the user makes for ambiguous logs (Tyto/RCbenchmark format; the native format has
/// one meaning per column and ignores them, except `decimal`).
struct BenchReadOptions {
  SignPolicy thrust_sign = SignPolicy::kAuto;  ///< the thrust's sign
  SignPolicy current_sign = SignPolicy::kAuto;  ///< applies to the electrical power too
  /// Quantity -> header name, overriding the automatic choice ("rpm" -> "Motor Optical Speed
  /// (RPM)") or adding a column the format does not name (motor_temp_c -> "Temp 1 (degC)").
  std::map<BenchColumn, std::string> columns;
  DecimalSeparator decimal = DecimalSeparator::kAuto;  ///< point, comma, or detected from the cells
};

}  // namespace propulsion_estimator
