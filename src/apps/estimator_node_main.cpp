#include <exception>

#include <ros/ros.h>

#include "propulsion_estimator/ros/estimator_node.h"
#include "propulsion_estimator/ros/node_help.h"

int main(int argc, char** argv) {
  if (propulsion_estimator::answeredHelp(argc, argv)) return 0;
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
