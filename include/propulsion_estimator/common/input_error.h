#pragma once

#include <stdexcept>
#include <string>

namespace propulsion_estimator {

/// Raised for any refused input and for a run its inputs make impossible. what() is one line that
/// names the source (file, line, key, column, option, parameter) and the offending value, ready to
/// be shown to the user as is. Thrown as such for a file that cannot be read or written; the kinds
/// of content refused have their own subclasses (ConfigError, DataError, SimulationError), so a
/// caller that only reports catches this one.
class InputError : public std::runtime_error {
 public:
  /// `message`: one line naming the input and the problem.
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace propulsion_estimator
