#include <cstdio>
#include <cstring>
#include <exception>

#include <ros/ros.h>

#include "propulsion_estimator/ros/estimator_node.h"

int main(int argc, char** argv) {
  // Its settings are ROS parameters: --help says where, instead of waiting for a ROS master.
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::puts(
          "estimator_node: the propulsion estimator as a ROS node. Its settings are private parameters\n"
          "(~model, ~urdf_file, ~motor_channels, capability/..., docs/node.md); start it with\n"
          "  roslaunch propulsion_estimator estimator.launch model:=MODEL.yaml\n"
          "or rosrun propulsion_estimator estimator_node _model:=MODEL.yaml with a ROS master running.");
      return 0;
    }
  }
  ros::init(argc, argv, "propulsion_estimator");
  // Outside the try: when the last node handle goes, roscpp shuts down and its logging with it.
  ros::NodeHandle nh, private_nh("~");
  try {
    propulsion_estimator::EstimatorNode node(nh, private_nh);
    ros::spin();
  } catch (const std::exception& e) {  // InputError: a refused parameter, model or URDF
    ROS_FATAL_STREAM(e.what());
    return 1;
  }
  return 0;
}
