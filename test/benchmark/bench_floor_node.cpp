// The end-to-end benchmark's transport floor (make bench, scripts/bench_node.py): a roscpp node
// that subscribes to what estimator_node subscribes to, RCOut as a ShapeShifter and the battery,
// with the same queues and TCP_NODELAY, and does nothing with them. Its CPU share and memory are
// what roscpp alone costs at the benchmark's rates. Prints the messages received when stopped.
//
// By default the callbacks run the way most roscpp nodes receive: roscpp's network thread queues
// each message and ros::spin() hands it to the callback. --inline runs them in the network thread
// itself (InlineCallbackQueue), as estimator_node receives: the floor of that way of receiving.
#include <atomic>
#include <iostream>

#include <CLI/CLI.hpp>
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>
#include <topic_tools/shape_shifter.h>

#include "propulsion_estimator/ros/inline_callback_queue.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "bench_floor");
  CLI::App app{"Receives RCOut and the battery and does nothing (make bench's transport floor)."};
  bool in_network_thread = false;
  app.add_flag("--inline", in_network_thread, "run the callbacks in roscpp's network thread");
  CLI11_PARSE(app, argc, argv);

  std::atomic<long> rc_out{0}, battery{0};
  propulsion_estimator::InlineCallbackQueue inline_queue;
  ros::NodeHandle nh;
  if (in_network_thread) nh.setCallbackQueue(&inline_queue);
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  ros::Subscriber rc_out_sub = nh.subscribe<topic_tools::ShapeShifter>(
      "/mavros/rc/out", 500, [&rc_out](const topic_tools::ShapeShifter::ConstPtr&) { ++rc_out; }, ros::VoidConstPtr(),
      hints);
  ros::Subscriber battery_sub = nh.subscribe<sensor_msgs::BatteryState>(
      "/mavros/battery", 5, [&battery](const sensor_msgs::BatteryState::ConstPtr&) { ++battery; }, ros::VoidConstPtr(),
      hints);
  ros::spin();
  std::cout << "{\"rc_out_received\": " << rc_out << ", \"battery_received\": " << battery << "}" << std::endl;
  return 0;
}
