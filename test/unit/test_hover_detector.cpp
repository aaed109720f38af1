#include <cmath>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/estimation/hover_detector.h"
#include "propulsion_estimator/estimation/time_window.h"

namespace pe = propulsion_estimator;

namespace {

pe::HoverSample sample(double thrust_n, double tilt_rad = NAN, double vz = NAN, double az = NAN) {
  return pe::HoverSample{thrust_n, thrust_n / 9.80665, tilt_rad, vz, az};
}

// Feeds 3 s at 50 Hz of samples made by `make(k)` and returns the final verdict.
template <typename F>
pe::HoverVerdict feed(pe::HoverDetector& detector, F make) {
  pe::HoverVerdict verdict;
  for (int k = 0; k < 150; ++k) verdict = detector.add(k * 0.02, make(k));
  return verdict;
}

}  // namespace

TEST(TimeWindow, EvictsByAgeAndByCapacity) {
  pe::TimeWindow<int> window(1.0, 4);
  for (int k = 0; k < 3; ++k) window.push(k * 0.4, k);  // 0, 0.4, 0.8
  EXPECT_EQ(window.size(), 3u);
  window.push(1.2, 3);  // 0.0 is now older than 1.2 - 1.0
  EXPECT_EQ(window.size(), 3u);
  EXPECT_EQ(window[0], 1);
  EXPECT_DOUBLE_EQ(window.span(), 0.8);
  window.push(1.3, 4);
  window.push(1.35, 5);  // full: the oldest goes
  EXPECT_EQ(window.size(), 4u);
  EXPECT_EQ(window[0], 2);
}

TEST(HoverDetector, SteadyThrustIsHoverOnceTheWindowIsFull) {
  pe::HoverDetector detector(pe::HoverConfig{}, 200);
  EXPECT_EQ(detector.add(0.0, sample(12.9)).blocker, pe::HoverBlocker::kWindowFilling);
  const pe::HoverVerdict verdict = feed(detector, [](int k) { return sample(12.9 + 0.1 * std::sin(k)); });
  EXPECT_TRUE(verdict.hovering);
  EXPECT_NEAR(verdict.mean_thrust_n, 12.9, 0.05);
  EXPECT_GE(verdict.span_s, 1.6);
  EXPECT_TRUE(std::isnan(verdict.max_tilt_rad));
}

TEST(HoverDetector, EachConditionBlocksHover) {
  const pe::HoverConfig config;
  {
    pe::HoverDetector d(config, 200);
    EXPECT_EQ(feed(d, [](int k) { return sample(k % 2 ? 11.0 : 14.0); }).blocker, pe::HoverBlocker::kThrustUnsteady);
  }
  {
    pe::HoverDetector d(config, 200);
    EXPECT_EQ(feed(d, [](int) { return sample(12.9, 6.0 * M_PI / 180.0); }).blocker, pe::HoverBlocker::kTilted);
  }
  {
    pe::HoverDetector d(config, 200);
    EXPECT_EQ(feed(d, [](int) { return sample(12.9, 0.0, 0.7); }).blocker, pe::HoverBlocker::kClimbingOrSinking);
  }
  {
    pe::HoverDetector d(config, 200);
    EXPECT_EQ(feed(d, [](int) { return sample(12.9, 0.0, 0.0, 1.5); }).blocker, pe::HoverBlocker::kAccelerating);
  }
  {
    pe::HoverDetector d(config, 200);  // armed and idling on the ground: steady, but it holds 0.1 kg
    EXPECT_EQ(feed(d, [](int) { return sample(1.0); }).blocker, pe::HoverBlocker::kLowThrust);
  }
  {
    pe::HoverDetector d(config, 200);  // within the limits
    EXPECT_TRUE(feed(d, [](int) { return sample(12.9, 4.0 * M_PI / 180.0, 0.5, 0.5); }).hovering);
  }
}

TEST(HoverDetector, DescribesWhyNotHovering) {
  pe::HoverDetector d(pe::HoverConfig{}, 200);
  feed(d, [](int) { return sample(12.9, 0.0, 0.9); });
  EXPECT_EQ(pe::describe(d.verdict(), d.config()),
            "not hovering: vertical speed 0.9 m/s (limit 0.6 m/s); window 101 samples over 2 s, mean thrust 12.9 N "
            "(1.32 kg), thrust std 0 %, max tilt 0 deg, max |vz| 0.9 m/s");
}

TEST(HoverConfig, RefusesNonsense) {
  pe::HoverConfig config;
  config.window_s = 0.0;
  try {
    config.validate();
    FAIL();
  } catch (const pe::ConfigError& e) {
    EXPECT_STREQ(e.what(), "hover/window_s: must be a positive number, got 0");
  }
  config = pe::HoverConfig{};
  config.min_window_fill = 1.5;
  try {
    config.validate();
    FAIL();
  } catch (const pe::ConfigError& e) {
    EXPECT_STREQ(e.what(), "hover/min_window_fill: 1.5 is outside 0..1 (must be positive)");
  }
  config.min_window_fill = 1.0;  // within 0..1, but the samples never span the whole window
  try {
    config.validate();
    FAIL();
  } catch (const pe::ConfigError& e) {
    EXPECT_STREQ(e.what(), "hover/min_window_fill: 1 is never met: the samples span less than the whole window");
  }
}
