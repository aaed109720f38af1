// The battery current with every motor stopped, measured on a flight's ground before arming and
// after disarming: the avionics' draw the current view takes out.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "propulsion_estimator/gap/ground_draw.h"

namespace pe = propulsion_estimator;
namespace gap = propulsion_estimator::gap;

namespace {

// 13 s: disarmed (900 us) for 3 s, flying at 1500 us for 7 s, disarmed again for 3 s; rc/out at
// 20 Hz, the battery at 10 Hz drawing 0.8 A on the ground (5 A in the second after disarming,
// while the rotors spin down) and 15 A in flight, reported negative as MAVROS gives PX4's.
pe::FlightStreams groundAndFlight() {
  pe::FlightStreams streams;
  streams.motors = 4;
  for (int i = 0; i < 260; ++i) {
    pe::RcOutFrame frame;
    frame.time_s = i / 20.0;
    const bool flying = frame.time_s >= 3.0 && frame.time_s < 10.0;
    for (int k = 0; k < 4; ++k) frame.pwm_us[k] = flying ? 1500.0 : 900.0;
    streams.rc_out.push_back(frame);
  }
  for (int i = 0; i < 130; ++i) {
    const double t = i / 10.0;
    const double current = t >= 3.0 && t < 10.0 ? 15.0 : t >= 10.0 && t < 11.0 ? 5.0 : 0.8 + 0.01 * (i % 3 - 1);
    streams.battery.push_back({t, 12.0, -current});
  }
  return streams;
}

}  // namespace

TEST(GroundDraw, IsTheMedianCurrentWithEveryMotorStoppedAndSettled) {
  const gap::GroundDraw draw = gap::measureGroundDraw(groundAndFlight(), 4, 1000.0, 1.0, 0.5);
  // 1.0-2.9 s before arming and 11.0-12.9 s after disarming: the first second of each is settling.
  EXPECT_EQ(draw.readings, 40);
  EXPECT_NEAR(draw.current_a, 0.8, 0.0101);
}

TEST(GroundDraw, NoneWhileAMotorIsCommandedAboveStoppedOrTooFewReadings) {
  pe::FlightStreams streams = groundAndFlight();
  for (pe::RcOutFrame& frame : streams.rc_out) frame.pwm_us[2] = std::max(frame.pwm_us[2], 1050.0);
  const gap::GroundDraw spinning = gap::measureGroundDraw(streams, 4, 1000.0, 1.0, 0.5);
  EXPECT_EQ(spinning.readings, 0);
  EXPECT_TRUE(std::isnan(spinning.current_a));

  // Settling for all but 0.45 s of each ground stretch leaves 8 readings; for all of it, none.
  EXPECT_EQ(gap::measureGroundDraw(groundAndFlight(), 4, 1000.0, 2.55, 0.5).readings, 8);
  const gap::GroundDraw short_ground = gap::measureGroundDraw(groundAndFlight(), 4, 1000.0, 3.0, 0.5);
  EXPECT_LT(short_ground.readings, gap::kMinGroundDrawReadings);
  EXPECT_TRUE(std::isnan(short_ground.current_a));
}

TEST(GroundDraw, LeavesOutReadingsWithoutACurrentOrAFreshCommand) {
  pe::FlightStreams streams = groundAndFlight();
  for (pe::BatteryReading& reading : streams.battery) reading.current_a = pe::kNaN;
  EXPECT_EQ(gap::measureGroundDraw(streams, 4, 1000.0, 1.0, 0.5).readings, 0);
  // rc/out stops at 2 s: readings more than 0.5 s after its last frame (1.95 s) have no command in force.
  streams = groundAndFlight();
  streams.rc_out.resize(40);
  EXPECT_EQ(gap::measureGroundDraw(streams, 4, 1000.0, 1.0, 0.5).readings, 15);
}

TEST(GroundDraw, KeepsTheSignOfASensorsOffsetAtRest) {
  // ArduPilot's sign (discharge positive): a sensor reading -0.05 A at rest is an offset, not a draw.
  pe::FlightStreams streams = groundAndFlight();
  for (pe::BatteryReading& reading : streams.battery) {
    reading.current_a = reading.time_s >= 3.0 && reading.time_s < 10.0 ? 15.0 : -0.05;
  }
  EXPECT_DOUBLE_EQ(gap::measureGroundDraw(streams, 4, 1000.0, 1.0, 0.5).current_a, -0.05);
  // MAVROS's sign for PX4 (discharge negative): the same offset reads +0.05 A.
  for (pe::BatteryReading& reading : streams.battery) reading.current_a = -reading.current_a;
  EXPECT_DOUBLE_EQ(gap::measureGroundDraw(streams, 4, 1000.0, 1.0, 0.5).current_a, -0.05);
}

TEST(GroundDraw, AMotorIsStoppedAtMost1000UsAnd10UsBelowTheBenchsLowest) {
  pe::ModelDomain domain;
  domain.pwm_min_us = 1200.0;
  EXPECT_DOUBLE_EQ(gap::stoppedPwmUs(domain), 1000.0);
  domain.pwm_min_us = 1000.0;
  EXPECT_DOUBLE_EQ(gap::stoppedPwmUs(domain), 990.0);
}
