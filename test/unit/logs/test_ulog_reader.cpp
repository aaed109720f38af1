// The PX4 ULog reader: a simulated flight written by the ULog writer in PX4 1.12's and newer
// layouts comes back as the simulator emitted it (the round trip; the ESC telemetry on each motor,
// in the newer layout through esc_report.actuator_function), and each damaged file keeps
// what came before and says where it broke, in one line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/logs/ulog_flight_reader.h"
#include "propulsion_estimator/logs/ulog_writer.h"
#include "propulsion_estimator/sim/flight/ulog_flight_sink.h"
#include "simulated_flight_logs.h"

namespace pe = propulsion_estimator;

namespace {

// A short simulated flight, recorded and written as a ULog in `layout`.
std::string simulate(pe::sim::UlogLayout layout, RecordingFlightSink* recorded) {
  pe::sim::UlogFlightSink ulog(layout, 1100.0, 1950.0);
  simulateShortFlight(recorded, &ulog);
  return ulog.bytes();
}

pe::FlightLogOptions options(int motors = 4) {
  pe::FlightLogOptions o;
  o.motors = motors;
  return o;
}

std::string refusal(const std::string& bytes) {
  try {
    pe::UlogFlightReader reader(bytes, "f.ulg");
    return reader.refusal();
  } catch (const pe::InputError& e) {
    return std::string("throws: ") + e.what();
  }
}

}  // namespace

TEST(UlogReader, ReadsBackAPx4v1_12LogAsTheSimulatorWroteIt) {
  RecordingFlightSink sim;
  const pe::UlogFlightReader reader(simulate(pe::sim::UlogLayout::kPx4v1_12, &sim), "f.ulg");
  EXPECT_EQ(reader.refusal(), "");
  EXPECT_NEAR(reader.durationS(), sim.rc_out.back().time_s - sim.rc_out.front().time_s, 0.05);
  const pe::FlightStreams streams = reader.read(options());
  expectRoundTrip(streams, sim, 0.0);
  expectEscRoundTrip(streams, sim);
  EXPECT_EQ(streams.notes.front(), "rc_out: actuator_outputs[0].output[0..3] (us)");
  EXPECT_EQ(reader.file().infoText("ver_sw_release"), "v1.12.3");
  // A rosbag's topic given for a signal is not silently dropped: the notes say it was not used.
  pe::FlightLogOptions with_topic = options();
  with_topic.sources["battery"] = "/my/battery";
  EXPECT_EQ(reader.read(with_topic).notes.back(),
            "sources given (battery=/my/battery) not used: a ULog is read from its own messages, named above");
}

TEST(UlogReader, ReadsTheNewerLayoutByFieldNames) {
  RecordingFlightSink sim;
  const pe::UlogFlightReader reader(simulate(pe::sim::UlogLayout::kPx4v1_14, &sim), "f.ulg");
  // actuator_motors only: the PWM range is required, and the outputs map through it.
  try {
    reader.read(options());
    ADD_FAILURE() << "read without a PWM range";
  } catch (const pe::ConfigError& e) {
    EXPECT_STREQ(e.what(), "f.ulg: rc_out: only actuator_motors (normalised) is logged: give the PWM range it maps onto");
  }
  pe::FlightLogOptions o = options();
  o.pwm_min_us = 1100.0;
  o.pwm_max_us = 1950.0;
  const pe::FlightStreams streams = reader.read(o);
  expectRoundTrip(streams, sim, 1e-3);
  expectEscRoundTrip(streams, sim);
  EXPECT_EQ(streams.notes.front(), "rc_out: actuator_motors[0].control[0..3] (0..1 mapped onto the PWM range given; "
                                   "NaN, a stopped motor, as 0 us)");
  // The simulated vehicle stands disarmed before take-off: PX4 logs its motors NaN, read as not driven.
  EXPECT_EQ(streams.rc_out.front().pwm_us[0], 0.0);
  // Up to its twelve controls are read.
  o.motors = 8;
  EXPECT_NO_THROW(reader.read(o));
}

TEST(UlogReader, RefusesWhatIsNotAULogOrHasNoData) {
  EXPECT_EQ(refusal("ULog"), "throws: f.ulg: not a ULog (it does not start with the 16-byte ULog header)");
  pe::ulog::Writer empty(0);
  EXPECT_EQ(refusal(empty.bytes()), "throws: f.ulg: no data messages");
  pe::ulog::Writer unknown_flag(0);
  unknown_flag.flagBits();
  std::string bytes = unknown_flag.bytes();
  bytes[16 + 3 + 8] = 2;  // incompat_flags[0] bit 1: unknown
  EXPECT_EQ(refusal(bytes), "throws: f.ulg: at byte 16: B (flag bits): incompatible flag 0 = 2 unknown to this reader");
  EXPECT_THROW(pe::UlogFlightReader("/nonexistent.ulg"), pe::InputError);
}

TEST(UlogReader, KeepsWhatCameBeforeATruncationOrACorruptMessage) {
  RecordingFlightSink sim;
  const std::string whole = simulate(pe::sim::UlogLayout::kPx4v1_12, &sim);
  const std::size_t cut = whole.size() / 2;
  const pe::UlogFlightReader truncated(whole.substr(0, cut), "f.ulg");
  EXPECT_NE(truncated.refusal().find("f.ulg: at byte "), std::string::npos);
  EXPECT_NE(truncated.refusal().find(" message: truncated ("), std::string::npos) << truncated.refusal();
  const pe::FlightStreams half = truncated.read(options());
  EXPECT_GT(half.rc_out.size(), sim.rc_out.size() / 3);
  EXPECT_LT(half.rc_out.size(), sim.rc_out.size());
  EXPECT_NEAR(half.rc_out[10].pwm_us[2], sim.rc_out[10].channels[2], 1e-3);

  // A data message whose msg_id no subscription announced: corrupt from there on.
  pe::ulog::Writer writer(1000);
  writer.format("battery_status:uint64_t timestamp;float voltage_v;");
  writer.format("actuator_outputs:uint64_t timestamp;uint32_t noutputs;float[4] output;");
  writer.subscribe(0, "battery_status");
  writer.subscribe(1, "actuator_outputs");
  for (int i = 0; i < 3; ++i) {
    writer.data(0, pe::ulog::Payload().put<std::uint64_t>(1000 + 100000 * i).put(12.0f));
    writer.data(1, pe::ulog::Payload().put<std::uint64_t>(1000 + 100000 * i).put<std::uint32_t>(4).put(1500.0f)
                       .put(1500.0f).put(1500.0f).put(1500.0f));
  }
  const std::size_t at = writer.bytes().size();
  writer.data(7, pe::ulog::Payload().put<std::uint64_t>(400000));
  const pe::UlogFlightReader corrupt(writer.bytes(), "f.ulg");
  EXPECT_EQ(corrupt.refusal(), "f.ulg: at byte " + std::to_string(at) +
                                   ": D message: msg_id 7, which no subscription (A message) announced");
  EXPECT_EQ(corrupt.read(options()).rc_out.size(), 3u);
  // Fewer outputs than motors, and no battery: the required signals' one-line refusals.
  try {
    corrupt.read(options(5));
    ADD_FAILURE();
  } catch (const pe::DataError& e) {
    EXPECT_STREQ(e.what(), "f.ulg: rc_out: actuator_outputs has no field output[4], fewer outputs than the 5 motors");
  }
}

// Text from the file (a topic's name with a newline, found by fuzz_ulog) keeps the refusal on one line.
TEST(UlogReader, KeepsARefusalOnOneLine) {
  pe::ulog::Writer writer(0);
  writer.format("battery_status:uint64_t timestamp;float voltage_v;");
  writer.subscribe(0, "vehicle\nattitude");
  EXPECT_EQ(refusal(writer.bytes()),
            "throws: f.ulg: no data messages (at byte 69: A message: subscribes to 'vehicle\\x0aattitude', "
            "which no format defines)");
}

// Each format-level refusal of a definition or an info message, in one line.
TEST(UlogReader, RefusesABadFormatOrInfoMessage) {
  const auto formatRefusal = [](const std::string& definition) {
    pe::ulog::Writer writer(0);
    writer.format(definition);
    return refusal(writer.bytes());
  };
  const std::string at16 = "throws: f.ulg: no data messages (at byte 16: ";
  EXPECT_EQ(formatRefusal("battery_status"), at16 + "F message: format 'battery_status' has no 'name:')");
  EXPECT_EQ(formatRefusal("b:float[0] x;"), at16 + "F message: b: field 'float[0] x' has a bad array length)");
  EXPECT_EQ(formatRefusal("b:floatx;"), at16 + "F message: b: field 'floatx' is not 'type name')");
  pe::ulog::Writer info(0);
  info.info("char[3] abc", "xyz");
  std::string bytes = info.bytes();
  bytes[16 + 3] = static_cast<char>(200);  // the key's length, past the message's end
  EXPECT_EQ(refusal(bytes), at16 + "I message: key longer than the message)");
}

TEST(UlogReader, FollowsAppendedDataAndCountsDropouts) {
  pe::ulog::Writer writer(0);
  writer.flagBits();
  writer.format("battery_status:uint64_t timestamp;float voltage_v;float current_a;");
  writer.format("actuator_outputs:uint64_t timestamp;uint32_t noutputs;float[4] output;");
  writer.subscribe(0, "battery_status");
  writer.subscribe(1, "actuator_outputs");
  const auto outputs = [](std::uint64_t t) {
    return pe::ulog::Payload().put(t).put<std::uint32_t>(4).put(1400.0f).put(1500.0f).put(1600.0f).put(1700.0f);
  };
  writer.data(1, outputs(0));
  writer.dropout(120);
  writer.data(0, pe::ulog::Payload().put<std::uint64_t>(500000).put(15.5f).put(-1.0f));
  std::string bytes = writer.bytes();
  // The logger stopped mid-message, then appended data after it (a crash's log, completed later).
  bytes += writer.bytes().substr(writer.bytes().size() - 10, 6);
  const std::uint64_t offset = bytes.size();
  pe::ulog::Writer tail(0);
  tail.data(1, outputs(2000000));
  bytes += tail.bytes().substr(16);
  std::memcpy(&bytes[16 + 3 + 16], &offset, 8);
  bytes[16 + 3 + 8] = 1;  // DATA_APPENDED
  const pe::UlogFlightReader reader(bytes, "f.ulg");
  EXPECT_EQ(reader.refusal(), "");
  EXPECT_EQ(reader.file().dropouts(), 1);
  const pe::FlightStreams streams = reader.read(options());
  ASSERT_EQ(streams.rc_out.size(), 2u);
  EXPECT_DOUBLE_EQ(streams.rc_out[1].time_s, 2.0);
  EXPECT_DOUBLE_EQ(streams.rc_out[1].pwm_us[3], 1700.0);
  ASSERT_EQ(streams.battery.size(), 1u);
  EXPECT_TRUE(std::isnan(streams.battery[0].current_a));  // -1: no current sensor
  EXPECT_EQ(streams.notes.back(), "1 logging dropouts, 120 ms in all");
  EXPECT_EQ(reader.durationS(), 2.0);
}
