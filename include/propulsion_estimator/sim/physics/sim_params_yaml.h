#pragma once

#include <string>

#include "propulsion_estimator/sim/physics/sim_params.h"

namespace propulsion_estimator {
namespace sim {

/// Reader of the simulator's parameter files (config/sim/*.yaml; schema in docs/simulator.md and in
/// config/sim/e300_dji2212_dji9443.yaml). Every value is required; unknown keys, wrong types and
/// values outside their physical range are refused with ConfigError "<file>:<line>: <key>: <problem>".
SimParams parseSimParamsYaml(const std::string& text, const std::string& source);
/// Reads and parses the parameter file `path`; InputError when it cannot be read.
SimParams loadSimParamsFile(const std::string& path);

}  // namespace sim
}  // namespace propulsion_estimator
