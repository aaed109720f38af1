#pragma once

#include <string>

#include "propulsion_estimator/sim/flight/flight_profile.h"

namespace propulsion_estimator {
namespace sim {

/// Reader of flight profiles (config/sim/*_flight.yaml; schema in docs/simulator.md and in
/// config/sim/default_flight.yaml). The URDF path is resolved against the profile's folder.
/// Refusals are ConfigError "<file>:<line>: <key>: <problem>", impossible segments included.
FlightProfile parseFlightProfileYaml(const std::string& text, const std::string& source);
/// Reads and parses the profile file `path`; InputError when it cannot be read.
FlightProfile loadFlightProfileFile(const std::string& path);

}  // namespace sim
}  // namespace propulsion_estimator
