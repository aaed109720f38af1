#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/estimation/hover_detector.h"

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

// Keeps the samples of each bin, to compare the window's aggregate with the samples it should hold.
struct Samples {
  std::vector<double> values;
  void add(double x) { values.push_back(x); }
  void merge(const Samples& other) { values.insert(values.end(), other.values.begin(), other.values.end()); }
};

TEST(BinnedWindow, KeepsTheLastSpanInWholeBins) {
  pe::BinnedWindow<Samples> window(6.4);  // 64 bins of 0.1 s
  EXPECT_DOUBLE_EQ(window.binLength(), 0.1);
  EXPECT_TRUE(window.empty());
  for (int k = 0; k < 100; ++k) window.add(k * 0.1 + 0.05, static_cast<double>(k));  // one sample per bin
  // The newest bin is 99; bins 36..99 are kept: the samples 36..99, spanning 6.3 s.
  const std::vector<double> kept = window.total().values;
  ASSERT_EQ(kept.size(), 64u);
  EXPECT_EQ(*std::min_element(kept.begin(), kept.end()), 36.0);
  EXPECT_NEAR(window.span(), 6.3, 1e-9);
  window.add(20.0, 1000.0);  // 10 s later: everything before has left
  EXPECT_EQ(window.total().values, std::vector<double>{1000.0});
  EXPECT_DOUBLE_EQ(window.span(), 0.0);
}

TEST(BinnedWindow, AnyRateInFixedMemory) {
  // 2 s at 5 kHz: 10,000 samples in the same 64 bins; the span stays within a bin of the window.
  pe::BinnedWindow<pe::RunningMoments> window(2.0);
  for (int k = 0; k < 50000; ++k) window.add(k * 2e-4, 1.0 + (k % 2 ? 0.01 : -0.01));
  const pe::RunningMoments moments = window.total();
  EXPECT_GE(window.span(), 2.0 * 63.0 / 64.0);
  EXPECT_LT(window.span(), 2.0);
  EXPECT_NEAR(static_cast<double>(moments.count), window.span() / 2e-4 + 1.0, 1.0);
  EXPECT_NEAR(moments.mean, 1.0, 1e-6);
  EXPECT_NEAR(std::sqrt(moments.variance()), 0.01, 1e-6);
}

TEST(BinnedWindow, ClearForgetsBinsAClockComingBackWouldMeet) {
  pe::BinnedWindow<Samples> window(6.4);
  for (int k = 0; k < 20; ++k) window.add(k * 0.1 + 0.05, 1.0);
  window.clear();
  // After a reset the clock restarts at 0.55 s and jumps to 1.55 s: bins 6..14 of before must not
  // come back.
  window.add(0.55, 2.0);
  window.add(1.55, 3.0);
  EXPECT_EQ(window.total().values, (std::vector<double>{2.0, 3.0}));
}

TEST(RunningMoments, MergedEqualsAddedOneByOne) {
  pe::RunningMoments all, left, right;
  for (int k = 0; k < 10; ++k) {
    const double x = 1e6 + k * k;  // a large mean: sums of squares would cancel
    all.add(x);
    (k < 4 ? left : right).add(x);
  }
  left.merge(right);
  EXPECT_EQ(left.count, all.count);
  EXPECT_DOUBLE_EQ(left.mean, all.mean);
  EXPECT_NEAR(left.m2, all.m2, 1e-6);
  EXPECT_NEAR(all.sampleVariance(), 7210.5 / 9.0, 1e-6);  // of k^2 for k = 0..9
}

TEST(HoverDetector, SteadyThrustIsHoverOnceTheWindowIsFull) {
  pe::HoverDetector detector(pe::HoverConfig{});
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
    pe::HoverDetector d(config);
    EXPECT_EQ(feed(d, [](int k) { return sample(k % 2 ? 11.0 : 14.0); }).blocker, pe::HoverBlocker::kThrustUnsteady);
  }
  {
    pe::HoverDetector d(config);
    EXPECT_EQ(feed(d, [](int) { return sample(12.9, 6.0 * M_PI / 180.0); }).blocker, pe::HoverBlocker::kTilted);
  }
  {
    pe::HoverDetector d(config);
    EXPECT_EQ(feed(d, [](int) { return sample(12.9, 0.0, 0.7); }).blocker, pe::HoverBlocker::kClimbingOrSinking);
  }
  {
    pe::HoverDetector d(config);
    EXPECT_EQ(feed(d, [](int) { return sample(12.9, 0.0, 0.0, 1.5); }).blocker, pe::HoverBlocker::kAccelerating);
  }
  {
    pe::HoverDetector d(config);  // armed and idling on the ground: steady, but it holds 0.1 kg
    EXPECT_EQ(feed(d, [](int) { return sample(1.0); }).blocker, pe::HoverBlocker::kLowThrust);
  }
  {
    pe::HoverDetector d(config);  // within the limits
    EXPECT_TRUE(feed(d, [](int) { return sample(12.9, 4.0 * M_PI / 180.0, 0.5, 0.5); }).hovering);
  }
}

TEST(HoverDetector, DescribesWhyNotHovering) {
  pe::HoverDetector d(pe::HoverConfig{});
  feed(d, [](int) { return sample(12.9, 0.0, 0.9); });
  EXPECT_EQ(pe::describe(d.verdict(), d.config()),
            "not hovering: vertical speed 0.9 m/s (limit 0.6 m/s); window 100 samples over 1.98 s, mean thrust 12.9 N "
            "(1.32 kg), thrust std 0 %, max tilt 0 deg, max |vz| 0.9 m/s; checks inactive: vertical acceleration");
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
    EXPECT_STREQ(e.what(),
                 "hover/min_window_fill: 1 is never reliably met: the window keeps its samples in 64 bins and spans at "
                 "least 0.9844 of hover/window_s");
  }
}
