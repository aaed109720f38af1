#pragma once

#include <string>

#include "propulsion_estimator/common/input_error.h"

namespace propulsion_estimator {

/// Refused measurements: a row, cell, header or metadata line of a bench log, or logs that as a
/// whole cannot determine what is asked of them (one voltage level, a constant column).
class DataError : public InputError {
 public:
  /// `message`: one line naming the file, where in it, and the problem.
  explicit DataError(const std::string& message) : InputError(message) {}
};

}  // namespace propulsion_estimator
