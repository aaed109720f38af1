#pragma once

#include <string>

#include "propulsion_estimator/common/input_error.h"

namespace propulsion_estimator {

/// A refused configuration: a key or value of a YAML file (model, simulator parameters, profile,
/// effects, manifest, tare file), a URDF, a node parameter or a command-line option.
class ConfigError : public InputError {
 public:
  /// `message`: one line naming the file, key or field and the value.
  explicit ConfigError(const std::string& message) : InputError(message) {}
};

}  // namespace propulsion_estimator
