#pragma once

#include <ros/node_handle.h>

#include "propulsion_estimator/onboard/node_parameters.h"

namespace propulsion_estimator {

/// Reads and validates the parameters of the node's private namespace (readNodeParameters) and
/// logs each loaded value once; throws ConfigError naming the parameter.
EstimatorNodeParams readEstimatorNodeParams(const ros::NodeHandle& private_nh);

}  // namespace propulsion_estimator
