#include <atomic>
#include <chrono>
#include <functional>
#include <future>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>
#include <ros/callback_queue.h>

#include "propulsion_estimator/ros/inline_callback_queue.h"

namespace pe = propulsion_estimator;

namespace {

// A callback that runs `body` and answers `result`.
class FakeCallback : public ros::CallbackInterface {
 public:
  FakeCallback(std::function<void()> body, CallResult result) : body_(std::move(body)), result_(result) {}
  CallResult call() override {
    ++calls;
    body_();
    return result_;
  }
  std::atomic<int> calls{0};

 private:
  std::function<void()> body_;
  CallResult result_;
};

}  // namespace

TEST(InlineCallbackQueue, RunsTheCallbackAtOnceInTheAddingThread) {
  ros::CallbackQueue fallback;
  pe::InlineCallbackQueue queue(&fallback);
  std::thread::id ran_in;
  auto callback = boost::make_shared<FakeCallback>([&ran_in] { ran_in = std::this_thread::get_id(); },
                                                   ros::CallbackInterface::Success);
  queue.addCallback(callback, 1);
  EXPECT_EQ(callback->calls, 1);
  EXPECT_EQ(ran_in, std::this_thread::get_id());
  EXPECT_TRUE(fallback.empty());
}

TEST(InlineCallbackQueue, HandsACallbackThatCannotRunNowToTheFallback) {
  ros::CallbackQueue fallback;
  pe::InlineCallbackQueue queue(&fallback);
  // roscpp's subscription queue answers TryAgain while the same subscription's callback runs elsewhere.
  auto callback = boost::make_shared<FakeCallback>([] {}, ros::CallbackInterface::TryAgain);
  queue.addCallback(callback, 1);
  EXPECT_EQ(callback->calls, 1);
  EXPECT_FALSE(fallback.empty());
}

TEST(InlineCallbackQueue, DropsWhatACallbackThrowsInsteadOfUnwindingTheNetworkThread) {
  ros::CallbackQueue fallback;
  pe::InlineCallbackQueue queue(&fallback);
  auto callback = boost::make_shared<FakeCallback>([] { throw std::runtime_error("bad message"); },
                                                   ros::CallbackInterface::Success);
  EXPECT_NO_THROW(queue.addCallback(callback, 1));
  EXPECT_EQ(callback->calls, 1);
  EXPECT_TRUE(fallback.empty());
}

TEST(InlineCallbackQueue, RemoveByIdWaitsForTheRunningCallback) {
  ros::CallbackQueue fallback;
  pe::InlineCallbackQueue queue(&fallback);
  std::promise<void> started, release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> finished{false};
  auto callback = boost::make_shared<FakeCallback>(
      [&] {
        started.set_value();
        released.wait();
        finished = true;
      },
      ros::CallbackInterface::Success);
  std::thread network([&] { queue.addCallback(callback, 7); });
  started.get_future().wait();
  std::atomic<bool> removed{false};
  std::thread unsubscribing([&] {
    queue.removeByID(7);
    removed = true;
  });
  // removeByID cannot return while the callback runs; once released, it does.
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(removed);
  release.set_value();
  unsubscribing.join();
  network.join();
  EXPECT_TRUE(finished);
  EXPECT_TRUE(removed);
}

TEST(InlineCallbackQueue, ACallbackMayShutDownAnotherSubscriberOfTheQueue) {
  ros::CallbackQueue fallback;
  pe::InlineCallbackQueue queue(&fallback);
  auto callback = boost::make_shared<FakeCallback>([&queue] { queue.removeByID(4); }, ros::CallbackInterface::Success);
  queue.addCallback(callback, 3);  // would deadlock with a non-recursive lock
  EXPECT_EQ(callback->calls, 1);
}
