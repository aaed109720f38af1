#pragma once

#include <cstdint>
#include <mutex>

#include <ros/callback_queue.h>
#include <ros/callback_queue_interface.h>
#include <ros/init.h>

namespace propulsion_estimator {

/// A roscpp callback queue that runs each callback at once, in the thread that adds it: for a
/// subscription, roscpp's network thread that has just read the message. This spares the hand-over
/// to a spinner thread (a futex wake and a context switch per message), which costs more than the
/// estimate itself (BENCHMARKS.md). Callbacks given to it must be short and must not block: while
/// one runs, the network thread reads nothing. Nor may a subscription's callback shut down its own
/// subscriber: roscpp holds that subscription's lock while it adds the callback.
///
/// A callback that cannot run now (roscpp answers TryAgain when the same subscription's callback is
/// already running in another thread) is handed to `fallback`, a queue a spinner serves. An
/// exception from a callback is logged and dropped: it must not unwind roscpp's thread.
class InlineCallbackQueue : public ros::CallbackQueueInterface {
 public:
  /// `fallback` must outlive this queue; by default the global queue that ros::spin() serves.
  explicit InlineCallbackQueue(ros::CallbackQueueInterface* fallback = ros::getGlobalCallbackQueue());

  /// Runs `callback` now in this thread, or hands it to the fallback queue when roscpp answers TryAgain.
  void addCallback(const ros::CallbackInterfacePtr& callback, std::uint64_t owner_id) override;
  /// Returns once no callback of `owner_id` runs (roscpp calls it when a subscriber shuts down,
  /// after which it adds none of that owner's).
  void removeByID(std::uint64_t owner_id) override;

 private:
  ros::CallbackQueueInterface* fallback_;
  /// Held while a callback runs. Recursive: a callback may shut down another subscriber of this queue.
  std::recursive_mutex calling_;
};

}  // namespace propulsion_estimator
