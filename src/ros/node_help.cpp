#include "propulsion_estimator/ros/node_help.h"

#include <cstdio>
#include <cstring>

namespace propulsion_estimator {

bool answeredHelp(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") != 0 && std::strcmp(argv[i], "-h") != 0) continue;
    // Its settings are ROS parameters: said where, instead of waiting for a ROS master.
    std::puts(
        "estimator_node: the propulsion estimator as a ROS node. Its settings are private parameters\n"
        "(~model, ~urdf_file, ~motor_channels, capability/..., docs/node.md); start it with\n"
        "  roslaunch propulsion_estimator estimator.launch model:=MODEL.yaml\n"
        "or rosrun propulsion_estimator estimator_node _model:=MODEL.yaml with a ROS master running.");
    return true;
  }
  return false;
}

}  // namespace propulsion_estimator
