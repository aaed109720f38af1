// The end-to-end benchmark's transport floor (make bench, scripts/bench_node.py): a roscpp node
// that subscribes to what estimator_node subscribes to, RCOut as a ShapeShifter and the battery,
// with the same queues and TCP_NODELAY, and does nothing with them. Its CPU share and memory are
// what roscpp alone costs at the benchmark's rates. Prints the messages received when stopped.
#include <iostream>

#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>
#include <topic_tools/shape_shifter.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "bench_floor");
  ros::NodeHandle nh;
  long rc_out = 0, battery = 0;
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  ros::Subscriber rc_out_sub = nh.subscribe<topic_tools::ShapeShifter>(
      "/mavros/rc/out", 20, [&rc_out](const topic_tools::ShapeShifter::ConstPtr&) { ++rc_out; }, ros::VoidConstPtr(),
      hints);
  ros::Subscriber battery_sub = nh.subscribe<sensor_msgs::BatteryState>(
      "/mavros/battery", 5, [&battery](const sensor_msgs::BatteryState::ConstPtr&) { ++battery; }, ros::VoidConstPtr(),
      hints);
  ros::spin();
  std::cout << "{\"rc_out_received\": " << rc_out << ", \"battery_received\": " << battery << "}" << std::endl;
  return 0;
}
