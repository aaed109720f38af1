#pragma once

#include <string>

#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {

/// Reads a vehicle from URDF. Rotors are the joints named rotor_<k>_joint (k = 1, 2, ...,
/// consecutive, in motor order); each rotor's thrust axis is its joint frame's +z and its spin
/// direction the sign of the joint axis' z component. The empty mass properties are the sum of
/// The links' `<inertial>` elements when at least one link has one. Throws ConfigError naming.
/// `source` for text that is not URDF, no rotors, missing or repeated rotor numbers, a joint that
/// closes a loop of links.
Vehicle vehicleFromUrdf(const std::string& xml, const std::string& source);
/// Reads the URDF file `path`: InputError when it cannot be read, else as vehicleFromUrdf.
Vehicle loadVehicleUrdf(const std::string& path);

}  // namespace propulsion_estimator
