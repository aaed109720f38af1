// Cutting a weighed flight into blocks: averages, signals, the current's sign and what is refused.
#include <cmath>
#include <string>

#include <random>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/gap/blocks.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace pe = propulsion_estimator;
namespace gap = propulsion_estimator::gap;

namespace {

// 20 s of level flight at 10 Hz: rc/out ramping 1500 -> 1519 us over each second, battery 12 V
// with -8 A (PX4's sign), level IMU at 1 g, rangefinder 1.5 m; one segment 2-12 s of 1.2 kg.
pe::Flight levelFlight() {
  pe::Flight flight;
  flight.name = "f.bag";
  flight.streams.motors = 4;
  for (int i = 0; i <= 200; ++i) {
    const double t = 0.1 * i;
    pe::RcOutFrame frame;
    frame.time_s = t;
    for (int k = 0; k < 4; ++k) frame.pwm_us[k] = 1500.0 + 2.0 * (i % 10);
    flight.streams.rc_out.push_back(frame);
    flight.streams.battery.push_back({t, 12.0, -8.0});
    pe::ImuReading imu;
    imu.time_s = t;
    imu.specific_force_m_s2 = Eigen::Vector3d(0.0, 0.0, pe::kStandardGravity);
    flight.streams.imu.push_back(imu);
    flight.streams.input(pe::input::Scalar::kRangefinder).push_back({t, 1.5});
  }
  flight.segments.push_back({2.0, 12.0, 1.2});
  return flight;
}

gap::BlockConfig config() {
  gap::BlockConfig config;
  config.motors = 4;
  return config;
}

}  // namespace

TEST(GapBlocks, AveragesEachBlockOfASegment) {
  const gap::FlightBlocks cut = gap::cutIntoBlocks(levelFlight(), 0, pe::Vehicle::quadX(0.225), config(), 0);
  EXPECT_TRUE(cut.assumptions.empty());
  EXPECT_TRUE(cut.has_imu);
  EXPECT_TRUE(cut.has_current);
  ASSERT_EQ(cut.blocks.size(), 10u);  // 2-12 s in 1 s blocks (the frame at 12 s alone is dropped)
  const gap::Block& block = cut.blocks.front();
  EXPECT_NEAR(block.pwm_us[0], 1509.0, 1e-9);
  EXPECT_NEAR(block.pwm_change_us, 18.0, 1e-6);  // a ramp in each block: its trend's change, no noise
  EXPECT_NEAR(block.voltage_v, 12.0, 1e-12);
  EXPECT_NEAR(block.current_a, 8.0, 1e-12) << "discharge counts positive whatever the autopilot's sign";
  EXPECT_NEAR(block.truth_n, 1.2 * pe::kStandardGravity, 1e-9);
  EXPECT_NEAR(block.axis_up[2], 1.0, 1e-12);
  EXPECT_NEAR(block.signals.value(pe::effects::Signal::kHeight), 1.5, 1e-12);
  EXPECT_TRUE(std::isnan(block.signals.value(pe::effects::Signal::kAirDensity))) << "no pressure or air temperature logged";
  EXPECT_TRUE(std::isnan(block.signals.value(pe::effects::Signal::kVerticalSpeed)));
  EXPECT_TRUE(block.hover);
  EXPECT_NEAR(block.accel_up_m_s2, 0.0, 1e-12);
  EXPECT_TRUE(gap::isQuasiSteady(block, 40.0, 0.8));
  EXPECT_FALSE(gap::isQuasiSteady(block, 10.0, 0.8));
}

TEST(GapBlocks, GroupsConsecutiveBlocksForTheTest) {
  gap::BlockConfig grouped = config();
  grouped.group_s = 5.0;
  const gap::FlightBlocks cut = gap::cutIntoBlocks(levelFlight(), 3, pe::Vehicle::quadX(0.225), grouped, 7);
  ASSERT_EQ(cut.blocks.size(), 10u);
  EXPECT_EQ(cut.blocks[0].flight, 3);
  EXPECT_EQ(cut.blocks[0].group, 7);
  EXPECT_EQ(cut.blocks[4].group, 7);
  EXPECT_EQ(cut.blocks[5].group, 8);
}

TEST(GapBlocks, NamesASegmentOutsideTheLogAndAFlightWithoutBattery) {
  pe::Flight flight = levelFlight();
  flight.segments.push_back({15.0, 30.0, 1.0});
  const gap::FlightBlocks cut = gap::cutIntoBlocks(flight, 0, pe::Vehicle::quadX(0.225), config(), 0);
  EXPECT_TRUE(cut.assumptions.empty());
  ASSERT_EQ(cut.skipped.size(), 1u);
  EXPECT_EQ(cut.skipped[0], "f.bag: segment 2 (15-30 s) lies outside the log's rc/out span 0.00-20.00 s");
  EXPECT_EQ(cut.blocks.size(), 10u);
  // A log that broke off before the segment: the line says why its span ends there.
  flight.damage = "f.bag: reading failed after 20 s: chunk 3: corrupt";
  EXPECT_EQ(gap::cutIntoBlocks(flight, 0, pe::Vehicle::quadX(0.225), config(), 0).skipped,
            std::vector<std::string>{"f.bag: segment 2 (15-30 s) lies outside the log's rc/out span 0.00-20.00 s (the "
                                     "log is damaged and read only up to there)"});
  // A segment before the log's first frame lies outside it whatever the damage.
  flight.segments.back() = {-5.0, 1.0, 1.0};
  EXPECT_EQ(gap::cutIntoBlocks(flight, 0, pe::Vehicle::quadX(0.225), config(), 0).skipped,
            std::vector<std::string>{"f.bag: segment 2 (-5-1 s) lies outside the log's rc/out span 0.00-20.00 s"});
  flight.segments.back() = {15.0, 30.0, 1.0};
  flight.damage.clear();

  flight.streams.battery.clear();
  const gap::FlightBlocks none = gap::cutIntoBlocks(flight, 0, pe::Vehicle::quadX(0.225), config(), 0);
  EXPECT_TRUE(none.blocks.empty());
  ASSERT_EQ(none.skipped.size(), 1u);
  EXPECT_EQ(none.skipped[0], "f.bag: no rc/out or battery messages");
}

namespace {

// Why a flight of one segment gave no block, and the cut.
std::string onlyProblem(const pe::Flight& flight, gap::FlightBlocks* cut) {
  *cut = gap::cutIntoBlocks(flight, 0, pe::Vehicle::quadX(0.225), config(), 0);
  EXPECT_TRUE(cut->blocks.empty());
  EXPECT_EQ(cut->skipped.size(), 1u);
  return cut->skipped.empty() ? std::string() : cut->skipped[0];
}

}  // namespace

TEST(GapBlocks, SaysWhyASegmentGaveNothingWithTheNumbers) {
  gap::FlightBlocks cut;
  pe::Flight flight = levelFlight();
  for (pe::BatteryReading& reading : flight.streams.battery) reading.time_s -= 100.0;  // all long before
  EXPECT_EQ(onlyProblem(flight, &cut), "f.bag: segment 1 (2-12 s) has no rc/out with a fresh battery voltage (101 of "
                                       "its 101 rc/out frames without a battery voltage within 1 s)");
  EXPECT_EQ(cut.frames_without_battery, 101);

  flight = levelFlight();
  for (pe::ImuReading& imu : flight.streams.imu) imu.time_s += 100.0;  // the IMU only after the segment
  EXPECT_EQ(onlyProblem(flight, &cut), "f.bag: segment 1 (2-12 s): none of its 10 blocks has the attitude on every "
                                       "frame (no IMU orientation within 1 s)");
  EXPECT_EQ(cut.blocks_without_attitude, 10);

  flight = levelFlight();
  flight.streams.rc_out.erase(flight.streams.rc_out.begin() + 15, flight.streams.rc_out.begin() + 150);
  EXPECT_EQ(onlyProblem(flight, &cut), "f.bag: segment 1 (2-12 s) holds no rc/out frame");
}

TEST(GapBlocks, WithoutImuTheWeightIsTheTruthAndItIsSaid) {
  pe::Flight flight = levelFlight();
  flight.streams.imu.clear();
  const gap::FlightBlocks cut = gap::cutIntoBlocks(flight, 0, pe::Vehicle::quadX(0.225), config(), 0);
  ASSERT_FALSE(cut.blocks.empty());
  EXPECT_NEAR(cut.blocks[0].truth_n, 1.2 * pe::kStandardGravity, 1e-9);
  ASSERT_EQ(cut.assumptions.size(), 1u);
  EXPECT_NE(cut.assumptions[0].find("no IMU"), std::string::npos);
}


// ESC telemetry at 5 Hz: ESC k reports 6000 + 100 k rpm, ESC 3 only in the first 4.4 s (then its
// packets drop), so its blocks from 4 s on hold too few fresh readings to average.
TEST(GapBlocks, AveragesEachRotorsSpeedWhereTelemetryCoversHalfTheBlock) {
  pe::Flight flight = levelFlight();
  for (int i = 0; i <= 100; ++i) {
    pe::EscTelemetryReading reading;
    reading.time_s = 0.2 * i;
    reading.escs = 4;
    for (int k = 0; k < 4; ++k) reading.rpm[k] = 6000.0 + 100.0 * k;
    if (reading.time_s > 4.4) reading.rpm[3] = pe::kNaN;
    flight.streams.esc.push_back(reading);
  }
  gap::BlockConfig short_timeout = config();
  short_timeout.signal_timeout_s = 0.3;
  const gap::FlightBlocks cut = gap::cutIntoBlocks(flight, 0, pe::Vehicle::quadX(0.225), short_timeout, 0);
  ASSERT_EQ(cut.blocks.size(), 10u);
  EXPECT_NEAR(cut.blocks[0].rpm[2], 6200.0, 1e-9);
  EXPECT_NEAR(cut.blocks[0].rpm[3], 6300.0, 1e-9);   // 2-3 s
  EXPECT_NEAR(cut.blocks[2].rpm[3], 6300.0, 1e-9);   // 4-5 s: 6 of 10 frames before the drop at 4.6 s
  EXPECT_TRUE(std::isnan(cut.blocks[3].rpm[3]));     // 5-6 s: none fresh
  EXPECT_NEAR(cut.blocks[3].rpm[0], 6000.0, 1e-9);
  EXPECT_TRUE(std::isnan(gap::cutIntoBlocks(levelFlight(), 0, pe::Vehicle::quadX(0.225), config(), 0).blocks[0].rpm[0]));
}

// A block's change of command is its trend's plus its noise's, whatever the rate it is logged at.
TEST(GapBlocks, TheChangeOfCommandIsTheTrendPlusTheNoiseWhateverTheRate) {
  const auto change = [](int rate_hz, double slope_us_per_s, bool noisy) {
    std::mt19937 draw(static_cast<unsigned>(rate_hz));
    std::normal_distribution<double> noise(0.0, 10.0);
    pe::Flight flight;
    flight.name = "rate.bag";
    flight.streams.motors = 4;
    for (int i = 0; i <= 12 * rate_hz; ++i) {
      const double t = static_cast<double>(i) / rate_hz;
      pe::RcOutFrame frame;
      frame.time_s = t;
      // The same noise of 10 us standard deviation on every motor (the collective's is 10 us).
      const double jitter = noisy ? noise(draw) : 0.0;
      for (int k = 0; k < 4; ++k) frame.pwm_us[k] = 1500.0 + slope_us_per_s * t + jitter;
      flight.streams.rc_out.push_back(frame);
      flight.streams.battery.push_back({t, 12.0, -8.0});
    }
    flight.segments.push_back({2.0, 12.0, 1.2});
    gap::BlockConfig config;
    config.motors = 4;
    return gap::cutIntoBlocks(flight, 0, pe::Vehicle::quadX(0.225), config, 0).blocks.front().pwm_change_us;
  };
  for (int rate : {20, 50, 100, 400}) {
    // A ramp of 30 us/s: its change across the block's frames (the last at 1 s less a frame).
    EXPECT_NEAR(change(rate, 30.0, false), 30.0 * (1.0 - 1.0 / rate), 1e-5) << rate;
    // Noise alone: about 3.7 standard deviations (its range over 20 frames on average) at every
    // rate, where the frames' range is 37 us at 20 Hz and about 60 us at 400 Hz.
    EXPECT_NEAR(change(rate, 0.0, true), 37.0, 0.15 * 37.0) << rate;
  }
}
