#include <ros/ros.h>

#include "propulsion_estimator/core/config_error.h"
#include "propulsion_estimator/ros/estimator_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "propulsion_estimator");
  try {
    propulsion_estimator::EstimatorNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const propulsion_estimator::ConfigError& e) {
    ROS_FATAL_STREAM(e.what());
    return 1;
  }
  return 0;
}
