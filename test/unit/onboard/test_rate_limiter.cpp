#include <gtest/gtest.h>

#include "propulsion_estimator/onboard/rate_limiter.h"

namespace pe = propulsion_estimator;

TEST(RateLimiter, AdmitsItsRateOnTheStamps) {
  pe::RateLimiter fifty_hz(50.0);
  int admitted = 0;
  // 1 s at 400 Hz: the first at once, then one per 20 ms slot, taken up to half a slot early.
  for (int k = 0; k < 400; ++k) admitted += fifty_hz.admit(100.0 + k * 0.0025);
  EXPECT_EQ(admitted, 51);
  admitted = 0;
  // 50 Hz passes whole, also jittering by +-3 ms.
  for (int k = 0; k < 50; ++k) admitted += fifty_hz.admit(200.0 + k * 0.02 + (k % 2 ? 0.003 : -0.003));
  EXPECT_EQ(admitted, 50);
  admitted = 0;
  for (int k = 0; k < 60; ++k) admitted += fifty_hz.admit(300.0 + k / 60.0);  // 60 Hz gives 50 Hz
  EXPECT_EQ(admitted, 50);
  EXPECT_TRUE(fifty_hz.admit(50.0));  // the stamps went back (a replay restarted)
  EXPECT_FALSE(fifty_hz.admit(50.005));
  EXPECT_TRUE(fifty_hz.admit(50.02));
  pe::RateLimiter every(0.0);
  for (int k = 0; k < 5; ++k) EXPECT_TRUE(every.admit(1.0));
}
