#pragma once

#include <stdexcept>
#include <string>

namespace propulsion_estimator {

// Raised for any refused input (file, key, row, parameter). what() is one line that names
// the source and the offending value, ready to be shown to the user as is.
class ConfigError : public std::runtime_error {
 public:
  explicit ConfigError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace propulsion_estimator
