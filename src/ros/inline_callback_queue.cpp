#include "propulsion_estimator/ros/inline_callback_queue.h"

#include <exception>

#include <ros/console.h>

namespace propulsion_estimator {

InlineCallbackQueue::InlineCallbackQueue(ros::CallbackQueueInterface* fallback) : fallback_(fallback) {}

void InlineCallbackQueue::addCallback(const ros::CallbackInterfacePtr& callback, std::uint64_t owner_id) {
  ros::CallbackInterface::CallResult result = ros::CallbackInterface::TryAgain;
  {
    std::lock_guard<std::recursive_mutex> lock(calling_);
    try {
      if (callback->ready()) result = callback->call();
    } catch (const std::exception& e) {
      ROS_ERROR_STREAM("callback threw (message dropped): " << e.what());
      return;
    }
  }
  if (result == ros::CallbackInterface::TryAgain) fallback_->addCallback(callback, owner_id);
}

void InlineCallbackQueue::removeByID(std::uint64_t owner_id) {
  std::lock_guard<std::recursive_mutex> lock(calling_);
  fallback_->removeByID(owner_id);
}

}  // namespace propulsion_estimator
