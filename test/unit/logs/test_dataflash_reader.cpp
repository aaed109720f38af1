// The ArduPilot DataFlash reader: a simulated flight written by the DataFlash writer comes back as
// the simulator emitted it (the round trip), and each damaged file keeps what came before and
// says where it broke, in one line.
#include <gtest/gtest.h>

#include <cmath>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/logs/dataflash_flight_reader.h"
#include "propulsion_estimator/logs/dataflash_writer.h"
#include "propulsion_estimator/sim/flight/dataflash_flight_sink.h"
#include "simulated_flight_logs.h"

namespace pe = propulsion_estimator;

namespace {

std::string simulate(RecordingFlightSink* recorded) {
  pe::sim::DataflashFlightSink log;
  simulateShortFlight(recorded, &log);
  return log.bytes();
}

pe::FlightLogOptions options(int motors = 4) {
  pe::FlightLogOptions o;
  o.motors = motors;
  return o;
}

std::string refusal(const std::string& bytes) {
  try {
    return pe::DataflashFlightReader(bytes, "f.bin").refusal();
  } catch (const pe::InputError& e) {
    return std::string("throws: ") + e.what();
  }
}

}  // namespace

TEST(DataflashReader, ReadsBackWhatTheSimulatorWrote) {
  RecordingFlightSink sim;
  const pe::DataflashFlightReader reader(simulate(&sim), "f.bin");
  EXPECT_EQ(reader.refusal(), "");
  const pe::FlightStreams read = reader.read(options());
  expectRoundTrip(read, sim, 0.0);
  expectEscRoundTrip(read, sim);
  EXPECT_EQ(read.notes.front(), "rc_out: RCOU C1..C4 (us)");
  pe::FlightLogOptions with_topic = options();
  with_topic.sources["battery"] = "/my/battery";
  EXPECT_EQ(reader.read(with_topic).notes.back(),
            "sources given (battery=/my/battery) not used: a DataFlash log is read from its own messages, named "
            "above");
}

TEST(DataflashReader, RefusesWhatIsNotADataflashLogOrHasNoTime) {
  EXPECT_EQ(refusal("\xa3\x95\x80"), "throws: f.bin: not a DataFlash log (it does not start with the FMT message of FMT)");
  EXPECT_EQ(refusal(pe::dataflash::Writer().bytes()), "throws: f.bin: no timed messages");
  EXPECT_THROW(pe::DataflashFlightReader("/nonexistent.bin"), pe::InputError);
}

TEST(DataflashReader, KeepsWhatCameBeforeATruncationOrACorruptMessage) {
  pe::dataflash::Writer writer;
  writer.define(1, "RCOU", "QHHHH", "TimeUS,C1,C2,C3,C4");
  writer.define(2, "BAT", "QBff", "TimeUS,Inst,Volt,Curr");
  for (int i = 0; i < 3; ++i) {
    writer.write(1, pe::BinaryPayload().put<std::uint64_t>(1000000 + 100000 * i).put<std::uint16_t>(1500)
                        .put<std::uint16_t>(1510).put<std::uint16_t>(1520).put<std::uint16_t>(1530));
    writer.write(2, pe::BinaryPayload().put<std::uint64_t>(1000000 + 100000 * i).put<std::uint8_t>(0).put(16.0f).put(9.0f));
  }
  const std::size_t end = writer.bytes().size();
  // Cut in a message: truncated.
  const pe::DataflashFlightReader truncated(writer.bytes().substr(0, end - 4), "f.bin");
  EXPECT_EQ(truncated.refusal(), "f.bin: at byte " + std::to_string(end - 20) + ": BAT: truncated (16 of 20 bytes)");
  const pe::FlightStreams before = truncated.read(options());
  EXPECT_EQ(before.rc_out.size(), 3u);
  EXPECT_EQ(before.battery.size(), 2u);
  EXPECT_DOUBLE_EQ(before.rc_out[2].time_s, 0.2);
  EXPECT_DOUBLE_EQ(before.rc_out[2].pwm_us[3], 1530.0);
  // A byte that starts no message, and a type no FMT defined.
  EXPECT_EQ(refusal(writer.bytes() + "\xa3\x94\x01"), "f.bin: at byte " + std::to_string(end) +
                                                           ": message header: expected 0xa3 0x95, found 0xa3 0x94");
  EXPECT_EQ(refusal(writer.bytes() + "\xa3\x95\x09"), "f.bin: at byte " + std::to_string(end) +
                                                           ": type 9: no FMT message defined it");
  // Not the FMT of FMT at the start.
  std::string bad = writer.bytes();
  bad[4] = 88;
  EXPECT_EQ(refusal(bad), "throws: f.bin: not a DataFlash log (it does not start with the FMT message of FMT)");
  // RCOU's FMT (bytes 89..177: header, FMT's type, length, name, format, labels) damaged: each
  // format-level refusal, with nothing timed before it.
  const auto rcouFmt = [&](std::size_t at, char byte) {
    std::string damaged = writer.bytes();
    damaged[at] = byte;
    return refusal(damaged);
  };
  const std::string fmt_at = "throws: f.bin: no timed messages (at byte 89: FMT: ";
  EXPECT_EQ(rcouFmt(93, 12), fmt_at + "RCOU: its columns take 19 bytes, its length says 12)");
  EXPECT_EQ(rcouFmt(103, 'H'), fmt_at + "RCOU: 6 format characters for 5 labels)");
  EXPECT_EQ(rcouFmt(99, 'X'), fmt_at + "RCOU: format character 'X' unknown)");
  EXPECT_EQ(rcouFmt(92, '\x80'), fmt_at + "FMT redefined with length 19)");
  // More motors than channels, and no battery.
  try {
    truncated.read(options(5));
    ADD_FAILURE();
  } catch (const pe::DataError& e) {
    EXPECT_STREQ(e.what(), "f.bin: rc_out: RCOU has no column C5, fewer channels than the 5 motors");
  }
}

TEST(DataflashReader, FindsColumnsByLabelInOlderLayouts) {
  // Older firmware: the instance column elsewhere, the ATT angles in centidegrees ('c', scaled),
  // CTUN instead of XKF1, no ESC.
  pe::dataflash::Writer writer;
  writer.define(10, "BAT", "QffB", "TimeUS,Volt,Curr,Inst");
  writer.define(11, "RCOU", "QHHHHHHHH", "TimeUS,C1,C2,C3,C4,C5,C6,C7,C8");
  writer.define(12, "CTUN", "Qfh", "TimeUS,Alt,CRt");
  writer.define(13, "ATT", "Qcccccc", "TimeUS,DesRoll,Roll,DesPitch,Pitch,DesYaw,Yaw");
  writer.define(14, "IMU", "Qfff", "TimeUS,AccX,AccY,AccZ");
  writer.write(10, pe::BinaryPayload().put<std::uint64_t>(5000000).put(15.0f).put(8.0f).put<std::uint8_t>(0));
  writer.write(10, pe::BinaryPayload().put<std::uint64_t>(5000000).put(1.0f).put(0.0f).put<std::uint8_t>(1));
  pe::BinaryPayload rcou;
  rcou.put<std::uint64_t>(5000100);
  for (int k = 0; k < 8; ++k) rcou.put<std::uint16_t>(1400 + k);
  writer.write(11, rcou);
  writer.write(12, pe::BinaryPayload().put<std::uint64_t>(5100000).put(2.5f).put<std::int16_t>(-30));
  writer.write(14, pe::BinaryPayload().put<std::uint64_t>(5100000).put(0.0f).put(0.0f).put(-9.8f));
  writer.write(13, pe::BinaryPayload().put<std::uint64_t>(5100000).put<std::int16_t>(0).put<std::int16_t>(0)
                       .put<std::int16_t>(0).put<std::int16_t>(0).put<std::int16_t>(0).put<std::int16_t>(9000));
  const pe::DataflashFlightReader reader(writer.bytes(), "old.bin");
  const pe::FlightStreams streams = reader.read(options(6));
  ASSERT_EQ(streams.battery.size(), 1u);  // instance 0 only
  EXPECT_DOUBLE_EQ(streams.battery[0].voltage_v, 15.0);
  EXPECT_DOUBLE_EQ(streams.rc_out[0].pwm_us[5], 1405.0);
  EXPECT_NEAR(streams.rc_out[0].time_s, 0.0001, 1e-12);
  EXPECT_DOUBLE_EQ(streams.altitude_m[0].value, 2.5);
  EXPECT_DOUBLE_EQ(streams.vertical_speed_m_s[0].value, -0.3);
  ASSERT_EQ(streams.imu.size(), 1u);
  // Yaw 90 deg (east in NED) is ENU yaw 0: the body's x axis points east, ENU x.
  EXPECT_LT((streams.imu[0].orientation * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitX()).norm(), 1e-9);
  EXPECT_NEAR(streams.imu[0].specific_force_m_s2.z(), 9.8, 1e-6);
  EXPECT_EQ(streams.notes.rbegin()[1], "motor_temperature: not in this log (no ESC)");
  EXPECT_EQ(streams.notes.back(), "esc_telemetry: not in this log (no ESC)");
}

// ArduPilot logs a row per ESC at its own time: the rows of one time are one reading, an ESC whose
// last report is older than half a second is not reported in it, a row without an RPM (a motor
// temperature alone) is no report, and an instance beyond the motors is ignored.
TEST(DataflashReader, MergesTheEscRowsOfOneTimeAndLeavesOutAStaleEsc) {
  pe::dataflash::Writer writer;
  writer.define(10, "BAT", "QffB", "TimeUS,Volt,Curr,Inst");
  writer.define(11, "RCOU", "QHH", "TimeUS,C1,C2");
  writer.define(12, "ESC", "QBfffhff", "TimeUS,Instance,RPM,Volt,Curr,Temp,CTot,MotTemp");
  writer.write(10, pe::BinaryPayload().put<std::uint64_t>(1000000).put(15.0f).put(8.0f).put<std::uint8_t>(0));
  writer.write(11, pe::BinaryPayload().put<std::uint64_t>(1000000).put<std::uint16_t>(1500).put<std::uint16_t>(1500));
  const auto esc = [&](std::uint64_t us, std::uint8_t instance, float rpm) {
    writer.write(12, pe::BinaryPayload().put(us).put(instance).put(rpm).put(15.5f).put(4.0f + instance)
                         .put<std::int16_t>(30).put(0.0f).put(NAN));
  };
  esc(1100000, 0, 6000.0f);
  esc(1100000, 1, 6100.0f);
  esc(1100000, 7, 9999.0f);  // no motor 8
  esc(1200000, 1, NAN);      // a temperature row
  esc(1800000, 1, 6200.0f);  // ESC 0 last reported 0.7 s before
  const pe::FlightStreams streams = pe::DataflashFlightReader(writer.bytes(), "esc.bin").read(options(2));
  ASSERT_EQ(streams.esc.size(), 2u);
  EXPECT_EQ(streams.esc[0].escs, 2);
  EXPECT_NEAR(streams.esc[0].time_s, 0.1, 1e-9);
  EXPECT_EQ(streams.esc[0].rpm[0], 6000.0);
  EXPECT_EQ(streams.esc[0].rpm[1], 6100.0);
  EXPECT_EQ(streams.esc[0].current_a[1], 5.0);
  EXPECT_EQ(streams.esc[0].voltage_v[0], 15.5);
  EXPECT_EQ(streams.esc[0].count[0], -1);
  EXPECT_TRUE(std::isnan(streams.esc[1].rpm[0]));
  EXPECT_TRUE(std::isnan(streams.esc[1].current_a[0]));
  EXPECT_EQ(streams.esc[1].rpm[1], 6200.0);
  EXPECT_EQ(streams.notes.back(), "esc_telemetry: ESC RPM, Curr, Volt per Instance (the rows of one time as one reading)");
}
