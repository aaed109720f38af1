#pragma once

#include <string>

#include "propulsion_estimator/common/input_error.h"

namespace propulsion_estimator {

/// A simulation that failed on its way: its state diverged, the battery emptied, the vehicle did not
/// reach what its profile asked or a bench experiment did not reach its end; the message names the
/// input that asked for it.
class SimulationError : public InputError {
 public:
  /// `message`: one line naming the input (profile, parameters) and what went wrong when.
  explicit SimulationError(const std::string& message) : InputError(message) {}
};

}  // namespace propulsion_estimator
