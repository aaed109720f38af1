// The flight bag reader on bags written here: what the simulator's bag writer writes comes back
// on the manifest's clock, and each refused bag gives its one-line message.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/Temperature.h>
#include <std_msgs/Float64.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <thread>

#include "propulsion_estimator/bag/bag_flight_sink.h"
#include "propulsion_estimator/bag/flight_bag_reader.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/codecs/rcout_codec.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;
namespace fs = std::filesystem;

namespace {

const ros::Time kStart(1600000000);

class FlightBagReader : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pe_bag_reader_" + std::string(testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  // The message on `reader.read(topics, motors)`'s refusal, or "" when it reads.
  static std::string refusal(const std::string& path, const pe::FlightBagTopics& topics = {}, int motors = 4) {
    try {
      pe::FlightBagReader(path).read(topics, motors);
    } catch (const pe::InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

pe::sim::RcOutSample rcOut(double time_s, std::vector<std::uint16_t> channels) { return {time_s, std::move(channels)}; }

pe::RcOutMessage rcOutMessage(std::vector<std::uint16_t> channels) {
  pe::RcOutMessage message;
  message.channels = std::move(channels);
  return message;
}

sensor_msgs::BatteryState battery(double voltage_v) {
  sensor_msgs::BatteryState message;
  message.voltage = static_cast<float>(voltage_v);
  return message;
}

// A bag with rc/out and battery only, for the refusals; `extra` writes more into it.
void writeMinimalBag(const std::string& path, const std::function<void(rosbag::Bag&)>& extra = {}) {
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  bag.write(pe::kRcOutTopic, kStart, pe::encodeRcOut(rcOutMessage({1500, 1500, 1500, 1500})));
  bag.write(pe::kBatteryTopic, kStart, battery(12.0));
  if (extra) extra(bag);
}

}  // namespace

TEST_F(FlightBagReader, ReadsWhatTheSimulatorWritesOnTheManifestsClock) {
  pe::sim::ImuSample imu;
  imu.time_s = 0.1;
  imu.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()));
  imu.linear_acceleration_m_s2 = Eigen::Vector3d(0.1, -0.2, 9.9);
  {
    pe::BagFlightSink sink(file("flight.bag"), rosbag::compression::Uncompressed);
    // The truth comes first: the clock starts at the bag's first message whatever its topic.
    pe::sim::TruthSample truth;
    truth.total_mass_kg = 1.315;
    sink.truth(truth);
    sink.rcOut(rcOut(0.02, {1600, 1610, 1620, 1630, 900, 900, 0, 0}));
    sink.rcOut(rcOut(0.04, {1601, 1611, 1621, 1631, 900, 900, 0, 0}));
    sink.battery({0.5, 12.25, -8.5, 0.9});
    sink.imu(imu);
    sink.pose({0.2, Eigen::Vector3d(1.0, 2.0, 3.5), Eigen::Quaterniond::Identity()});
    sink.velocity({0.3, Eigen::Vector3d(0.1, 0.2, -0.4), Eigen::Vector3d::Zero()});
    sink.staticPressure({0.4, 101000.5, 1.0, "base_link"});
    sink.airTemperature({0.6, 21.5, 0.1, "base_link"});
    sink.motorTemperature({0.7, 45.25, 0.5, "rotor_2_link"});
    sink.rangefinder({0.8, 2.5, 0.2, 8.0, 0.5});
    sink.rangefinder({0.85, std::numeric_limits<double>::infinity(), 0.2, 8.0, 0.5});  // beyond reach
    sink.rangefinder({0.9, -std::numeric_limits<double>::infinity(), 0.2, 8.0, 0.5});  // below reach
    pe::sim::EscTelemetrySample esc;
    esc.time_s = 0.45;
    esc.px4 = false;
    for (int k = 0; k < 4; ++k) esc.escs.push_back({6000.0 + k, 4.5 + k, 12.1, 40.0, static_cast<std::uint16_t>(7 + k)});
    sink.escTelemetry(esc);
    esc.time_s = 0.55;
    esc.px4 = true;
    sink.escTelemetry(esc);
  }
  const pe::FlightBagReader reader(file("flight.bag"));
  EXPECT_NEAR(reader.durationS(), 0.9, 1e-9);
  const pe::FlightStreams streams = reader.read({}, 4);

  EXPECT_EQ(streams.source, file("flight.bag"));
  EXPECT_EQ(streams.motors, 4);
  ASSERT_EQ(streams.rc_out.size(), 2u);
  EXPECT_NEAR(streams.rc_out[0].time_s, 0.02, 1e-9);
  EXPECT_EQ(streams.rc_out[0].pwm_us[0], 1600);
  EXPECT_EQ(streams.rc_out[1].pwm_us[3], 1631);
  EXPECT_EQ(streams.rc_out[1].pwm_us[4], 0);  // channels past the motors are not taken
  ASSERT_EQ(streams.battery.size(), 1u);
  EXPECT_NEAR(streams.battery[0].time_s, 0.5, 1e-9);
  EXPECT_DOUBLE_EQ(streams.battery[0].voltage_v, static_cast<double>(12.25f));
  EXPECT_DOUBLE_EQ(streams.battery[0].current_a, -8.5);  // PX4's sign, as logged
  ASSERT_EQ(streams.imu.size(), 1u);
  EXPECT_NEAR(streams.imu[0].time_s, 0.1, 1e-9);
  EXPECT_TRUE(streams.imu[0].orientation.isApprox(imu.orientation, 1e-12));
  EXPECT_TRUE(streams.imu[0].specific_force_m_s2.isApprox(Eigen::Vector3d(0.1, -0.2, 9.9), 1e-12));
  ASSERT_EQ(streams.altitude_m.size(), 1u);
  EXPECT_DOUBLE_EQ(streams.altitude_m[0].value, 3.5);
  ASSERT_EQ(streams.vertical_speed_m_s.size(), 1u);
  EXPECT_DOUBLE_EQ(streams.vertical_speed_m_s[0].value, -0.4);
  ASSERT_EQ(streams.horizontal_velocity.size(), 1u);
  EXPECT_DOUBLE_EQ(streams.horizontal_velocity[0].east_m_s, 0.1);
  EXPECT_DOUBLE_EQ(streams.horizontal_velocity[0].north_m_s, 0.2);
  // ArduPilot's ESCTelemetry and PX4's ESCStatus into one stream, each ESC on its channel; PX4's
  // has no packet count.
  ASSERT_EQ(streams.esc.size(), 2u);
  EXPECT_NEAR(streams.esc[0].time_s, 0.45, 1e-9);
  EXPECT_EQ(streams.esc[0].escs, 4);
  EXPECT_NEAR(streams.esc[0].rpm[2], 6002.0, 1e-3);
  EXPECT_NEAR(streams.esc[0].current_a[3], 7.5, 1e-6);
  EXPECT_NEAR(streams.esc[0].voltage_v[1], 12.1, 1e-6);
  EXPECT_EQ(streams.esc[0].count[1], 8);
  EXPECT_NEAR(streams.esc[1].time_s, 0.55, 1e-9);
  EXPECT_EQ(streams.esc[1].count[1], -1);
  EXPECT_FALSE(streams.esc[0].status);
  EXPECT_TRUE(streams.esc[1].status);
  const std::vector<std::size_t> counts = pe::signalCounts(streams);
  EXPECT_EQ(counts[counts.size() - 2], 1u);  // esc_telemetry
  EXPECT_EQ(counts.back(), 1u);              // esc_status
  ASSERT_EQ(streams.input(pe::input::Scalar::kStaticPressure).size(), 1u);
  EXPECT_DOUBLE_EQ(streams.input(pe::input::Scalar::kStaticPressure)[0].value, 101000.5);
  ASSERT_EQ(streams.input(pe::input::Scalar::kAirTemperature).size(), 1u);
  EXPECT_DOUBLE_EQ(streams.input(pe::input::Scalar::kAirTemperature)[0].value, 21.5);
  ASSERT_EQ(streams.input(pe::input::Scalar::kMotorTemperature).size(), 1u);
  EXPECT_NEAR(streams.input(pe::input::Scalar::kMotorTemperature)[0].time_s, 0.7, 1e-9);
  EXPECT_DOUBLE_EQ(streams.input(pe::input::Scalar::kMotorTemperature)[0].value, 45.25);
  ASSERT_EQ(streams.input(pe::input::Scalar::kRangefinder).size(), 1u);  // the readings out of reach are left out
  EXPECT_NEAR(streams.input(pe::input::Scalar::kRangefinder)[0].time_s, 0.8, 1e-9);
  EXPECT_DOUBLE_EQ(streams.input(pe::input::Scalar::kRangefinder)[0].value, 2.5);
}

TEST_F(FlightBagReader, LeavesTheStreamsOfMissingOptionalTopicsEmpty) {
  writeMinimalBag(file("minimal.bag"));
  const pe::FlightStreams streams = pe::FlightBagReader(file("minimal.bag")).read({}, 4);
  EXPECT_EQ(streams.rc_out.size(), 1u);
  EXPECT_EQ(streams.battery.size(), 1u);
  EXPECT_TRUE(streams.imu.empty());
  EXPECT_TRUE(streams.altitude_m.empty());
  EXPECT_TRUE(streams.vertical_speed_m_s.empty());
  EXPECT_TRUE(streams.input(pe::input::Scalar::kStaticPressure).empty());
  EXPECT_TRUE(streams.input(pe::input::Scalar::kAirTemperature).empty());
  EXPECT_TRUE(streams.input(pe::input::Scalar::kRangefinder).empty());
  EXPECT_TRUE(streams.input(pe::input::Scalar::kMotorTemperature).empty());
  EXPECT_TRUE(streams.horizontal_velocity.empty());
  EXPECT_TRUE(streams.esc.empty());
}

TEST_F(FlightBagReader, SkipsImuMessagesWithoutOrientation) {
  writeMinimalBag(file("imu.bag"), [](rosbag::Bag& bag) {
    sensor_msgs::Imu imu;
    imu.orientation.w = 1.0;
    imu.linear_acceleration.z = 9.8;
    bag.write(pe::kImuTopic, kStart + ros::Duration(0.1), imu);
    imu.orientation_covariance[0] = -1.0;  // REP-145: no orientation
    bag.write(pe::kImuTopic, kStart + ros::Duration(0.2), imu);
  });
  const pe::FlightStreams streams = pe::FlightBagReader(file("imu.bag")).read({}, 4);
  ASSERT_EQ(streams.imu.size(), 1u);
  EXPECT_NEAR(streams.imu[0].time_s, 0.1, 1e-9);
}

TEST_F(FlightBagReader, ReadsTheTopicsItIsGiven) {
  writeMinimalBag(file("renamed.bag"), [](rosbag::Bag& bag) {
    sensor_msgs::Temperature temperature;
    temperature.temperature = 30.0;
    bag.write("/esc/temperature", kStart + ros::Duration(1.0), temperature);
  });
  pe::FlightBagTopics topics;
  *topics.find("motor_temperature") = "/esc/temperature";
  // Two signals may read one topic.
  *topics.find("air_temperature") = "/esc/temperature";
  const pe::FlightStreams streams = pe::FlightBagReader(file("renamed.bag")).read(topics, 4);
  ASSERT_EQ(streams.input(pe::input::Scalar::kMotorTemperature).size(), 1u);
  EXPECT_DOUBLE_EQ(streams.input(pe::input::Scalar::kMotorTemperature)[0].value, 30.0);
  ASSERT_EQ(streams.input(pe::input::Scalar::kAirTemperature).size(), 1u);
  EXPECT_NEAR(streams.input(pe::input::Scalar::kAirTemperature)[0].time_s, 1.0, 1e-9);
}

TEST_F(FlightBagReader, NamesItsSignals) {
  pe::FlightBagTopics topics;
  EXPECT_EQ(pe::FlightBagTopics::names(),
            (std::vector<std::string>{"rc_out", "battery", "imu", "pose", "velocity", "static_pressure",
                                      "air_temperature", "rangefinder", "motor_temperature", "esc_telemetry",
                                      "esc_status"}));
  EXPECT_EQ(*topics.find("rc_out"), "/mavros/rc/out");
  EXPECT_EQ(*topics.find("velocity"), "/mavros/local_position/velocity_local");
  EXPECT_EQ(*topics.find("motor_temperature"), "/motor_temperature");
  EXPECT_EQ(topics.find("truth"), nullptr);
}

TEST_F(FlightBagReader, RefusesAFileThatIsNotABag) {
  EXPECT_EQ(refusal(file("absent.bag")), file("absent.bag") + ": no such file");
  std::ofstream(file("text.bag")) << "not a bag\n";
  EXPECT_EQ(refusal(file("text.bag")), file("text.bag") + ": not a readable bag: Error reading version line");
  { rosbag::Bag empty(file("empty.bag"), rosbag::bagmode::Write); }
  EXPECT_EQ(refusal(file("empty.bag")), file("empty.bag") + ": no messages");
}

// A record whose stated length runs past the file's end is refused before rosbag allocates it
// (fuzz_flight_bag's finding: 2.3 GB asked for by a 12 kB file), and so is a truncated bag.
TEST_F(FlightBagReader, RefusesARecordLongerThanTheFileBeforeRosbagReadsIt) {
  writeMinimalBag(file("good.bag"));
  std::ifstream in(file("good.bag"), std::ios::binary);
  const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string huge = good;
  huge.replace(13, 4, std::string("\xff\xff\xff\x7f", 4));  // the bag header record's header length
  std::ofstream(file("huge.bag"), std::ios::binary) << huge;
  EXPECT_EQ(refusal(file("huge.bag")), file("huge.bag") + ": not a readable bag: at byte 13: record header of "
                                           "2147483647 bytes, beyond the file's end (" + std::to_string(good.size()) +
                                           " bytes)");
  std::ofstream(file("cut.bag"), std::ios::binary) << good.substr(0, good.size() - 10);
  const std::string cut = refusal(file("cut.bag"));
  EXPECT_EQ(cut.rfind(file("cut.bag") + ": not a readable bag: at byte ", 0), 0u) << cut;
  const std::string remedy = "; `rosbag reindex` rebuilds its index from the whole records";
  EXPECT_EQ(cut.substr(cut.size() - std::min(cut.size(), remedy.size())), remedy) << cut;
  std::cout << "  " << cut << "\n";
}

// rosbag reads as many index entries as a record states, past its data if need be, and then a
// record length from the middle of the next record (fuzz_flight_bag's finding: 2.3 GB asked for).
TEST_F(FlightBagReader, RefusesAnIndexRecordStatingMoreEntriesThanItHolds) {
  const std::string found = repoPath("test/fuzz/regressions/flight_bag/oom-index-record-count-beyond-its-data");
  EXPECT_EQ(refusal(found), found + ": not a readable bag: at byte 9636: index record states 93 entries in 144 bytes"
                            "; `rosbag reindex` rebuilds its index from the whole records");
}

namespace {

// Where the value of header field `name` (a `size`-byte integer) lies in `bag`, from `from` on:
// each field is its length (4 bytes), "name=" and the value.
std::size_t fieldValueAt(const std::string& bag, const std::string& name, std::size_t size, std::size_t from = 0) {
  const std::uint32_t length = static_cast<std::uint32_t>(name.size() + 1 + size);
  const std::string field = std::string(reinterpret_cast<const char*>(&length), 4) + name + "=";
  const std::size_t at = bag.find(field, from);
  EXPECT_NE(at, std::string::npos) << name;
  return at + field.size();
}

template <typename T>
T integerAt(const std::string& bag, std::size_t at) {
  T value;
  std::memcpy(&value, bag.data() + at, sizeof(T));
  return value;
}

template <typename T>
void setIntegerAt(std::string* bag, std::size_t at, T value) {
  bag->replace(at, sizeof(T), std::string(reinterpret_cast<const char*>(&value), sizeof(T)));
}

}  // namespace

// rosbag reads as many connection and chunk-info records at the index position as the bag header
// counts, and as many index records after each chunk as its chunk info lists, past the last record
// if need be.
TEST_F(FlightBagReader, RefusesCountsThatRosbagWouldFollowPastTheLastRecord) {
  writeMinimalBag(file("good.bag"));
  std::ifstream in(file("good.bag"), std::ios::binary);
  const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto index_pos = integerAt<std::uint64_t>(good, fieldValueAt(good, "index_pos", 8));
  ASSERT_EQ(integerAt<std::uint32_t>(good, fieldValueAt(good, "conn_count", 4)), 2u);  // rc/out and battery
  ASSERT_EQ(integerAt<std::uint32_t>(good, fieldValueAt(good, "chunk_count", 4)), 1u);

  std::string connections = good;
  setIntegerAt<std::uint32_t>(&connections, fieldValueAt(good, "conn_count", 4), 100);
  std::ofstream(file("connections.bag"), std::ios::binary) << connections;
  EXPECT_EQ(refusal(file("connections.bag")),
            file("connections.bag") + ": not a readable bag: the bag header states 100 connections and 1 chunks at byte " +
                std::to_string(index_pos) + ", but only 3 records lie there; `rosbag reindex` rebuilds its index from the whole records");

  // The chunk info is the last record: its data, (connection, messages) pairs, ends the file.
  const std::size_t chunk_info = fieldValueAt(good, "chunk_pos", 8);
  const auto chunk_pos = integerAt<std::uint64_t>(good, chunk_info);
  const std::size_t count_at = fieldValueAt(good, "count", 4, chunk_info);
  ASSERT_EQ(integerAt<std::uint32_t>(good, count_at), 2u);
  ASSERT_EQ(integerAt<std::uint32_t>(good, good.size() - 20), 16u);  // its data length
  std::string short_data = good;
  setIntegerAt<std::uint32_t>(&short_data, count_at, 7);
  std::ofstream(file("short.bag"), std::ios::binary) << short_data;
  const std::string short_refusal = refusal(file("short.bag"));
  EXPECT_EQ(short_refusal.rfind(file("short.bag") + ": not a readable bag: at byte ", 0), 0u) << short_refusal;
  EXPECT_NE(short_refusal.find(": chunk info states 7 connections in 16 bytes"), std::string::npos) << short_refusal;

  std::string listed = short_data;
  setIntegerAt<std::uint32_t>(&listed, good.size() - 20, 56);
  for (std::uint32_t connection = 2; connection < 7; ++connection) {
    listed += std::string(reinterpret_cast<const char*>(&connection), 4) + std::string("\x01\x00\x00\x00", 4);
  }
  std::ofstream(file("listed.bag"), std::ios::binary) << listed;
  EXPECT_EQ(refusal(file("listed.bag")), file("listed.bag") + ": not a readable bag: the chunk at byte " +
                                             std::to_string(chunk_pos) +
                                             " lists 7 connections, but only 5 records follow it; `rosbag reindex` rebuilds its index from the whole records");
  EXPECT_EQ(refusal(file("good.bag")), "") << "the unedited bag is read";
}

// The registry tells a bag by its first bytes, not its name, and reads it through the interface.
TEST_F(FlightBagReader, IsTheRegistrysRosbagFormat) {
  pe::FlightLogFormats formats;
  formats.add(pe::flightBagFormat());
  EXPECT_EQ(formats.names(), std::vector<std::string>{"rosbag"});
  EXPECT_THROW(formats.add(pe::flightBagFormat()), std::invalid_argument);
  writeMinimalBag(file("flight.ulg"));
  const std::unique_ptr<pe::FlightLogReader> reader = formats.open(file("flight.ulg"));
  pe::FlightLogOptions options;
  options.sources["battery"] = "/power";  // a source the bag lacks: the required signal is missing
  EXPECT_THROW(reader->read(options), pe::DataError);
  options.sources.clear();
  const pe::FlightStreams streams = reader->read(options);
  EXPECT_EQ(streams.rc_out.size(), 1u);
  EXPECT_EQ(streams.battery.size(), 1u);
  options.sources["truth"] = "/sim/truth";
  EXPECT_THROW(reader->read(options), pe::ConfigError);

  const auto refusal = [&formats](const std::string& path) {
    try {
      formats.open(path);
    } catch (const pe::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(refusal(file("absent.bag")), file("absent.bag") + ": no such file");
  std::ofstream(file("text.bag")) << "not a\tbag \"at all\"\n";
  EXPECT_EQ(refusal(file("text.bag")),
            file("text.bag") + ": not a flight log of a known format (rosbag): it starts with \"not a\\x09bag \\x22a\"");
  std::ofstream(file("empty.bag")).flush();
  EXPECT_EQ(refusal(file("empty.bag")), file("empty.bag") + ": empty: not a flight log");
  std::ofstream(file("cut.bag")) << "#ROSBAG";
  EXPECT_EQ(refusal(file("cut.bag")), file("cut.bag") + ": a rosbag log cut short: it ends after 7 bytes, within its "
                                                        "first 12 (\"#ROSBAG V2.0\")");
}

TEST_F(FlightBagReader, RefusesABagWithoutARequiredTopic) {
  {
    rosbag::Bag bag(file("no_battery.bag"), rosbag::bagmode::Write);
    bag.write(pe::kRcOutTopic, kStart, pe::encodeRcOut(rcOutMessage({1500, 1500, 1500, 1500})));
  }
  EXPECT_EQ(refusal(file("no_battery.bag")), file("no_battery.bag") + ": /mavros/battery: no messages (a required topic)");
  {
    rosbag::Bag bag(file("no_rc_out.bag"), rosbag::bagmode::Write);
    bag.write(pe::kBatteryTopic, kStart, battery(12.0));
  }
  EXPECT_EQ(refusal(file("no_rc_out.bag")), file("no_rc_out.bag") + ": /mavros/rc/out: no messages (a required topic)");
  pe::FlightBagTopics topics;
  topics.battery = "/battery";
  writeMinimalBag(file("minimal.bag"));
  EXPECT_EQ(refusal(file("minimal.bag"), topics), file("minimal.bag") + ": /battery: no messages (a required topic)");
}

TEST_F(FlightBagReader, RefusesATopicOfAnotherType) {
  writeMinimalBag(file("imu_as_float.bag"), [](rosbag::Bag& bag) {
    bag.write(pe::kImuTopic, kStart, std_msgs::Float64());
  });
  EXPECT_EQ(refusal(file("imu_as_float.bag")),
            file("imu_as_float.bag") +
                ": /mavros/imu/data: expected sensor_msgs/Imu (md5sum 6a62c6daae103f4ff57a132d6f95cec2), got "
                "std_msgs/Float64 (md5sum fdb28210bfa9d7c91146260178d9a584)");
  {
    rosbag::Bag bag(file("rc_out_as_float.bag"), rosbag::bagmode::Write);
    bag.write(pe::kRcOutTopic, kStart, std_msgs::Float64());
    bag.write(pe::kBatteryTopic, kStart, battery(12.0));
  }
  EXPECT_EQ(refusal(file("rc_out_as_float.bag")),
            file("rc_out_as_float.bag") +
                ": /mavros/rc/out: expected mavros_msgs/RCOut (md5sum 52cacf104bab5ae3b103cfe176590713), got "
                "std_msgs/Float64 (md5sum fdb28210bfa9d7c91146260178d9a584)");
}

TEST_F(FlightBagReader, RefusesRcOutWithFewerChannelsThanMotors) {
  writeMinimalBag(file("quad.bag"), [](rosbag::Bag& bag) {
    bag.write(pe::kRcOutTopic, kStart + ros::Duration(2.5), pe::encodeRcOut(rcOutMessage({1500, 1500, 1500})));
  });
  EXPECT_EQ(refusal(file("quad.bag"), {}, 6), file("quad.bag") + ": /mavros/rc/out: at 0.000 s: 4 channels, fewer than the 6 motors");
  EXPECT_EQ(refusal(file("quad.bag"), {}, 4), file("quad.bag") + ": /mavros/rc/out: at 2.500 s: 3 channels, fewer than the 4 motors");
  EXPECT_EQ(refusal(file("quad.bag"), {}, 3), "");
}

TEST_F(FlightBagReader, ReadersOfDifferentBagsWorkOnThreads) {
  // rosbag loads and unloads a plugin per bag: unguarded, two threads opening bags soon fail.
  for (int t = 0; t < 4; ++t) writeMinimalBag(file("bag_" + std::to_string(t) + ".bag"));
  std::vector<std::thread> threads;
  std::vector<int> read(4, 0);
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 50; ++i) {
        const pe::FlightBagReader reader(file("bag_" + std::to_string(t) + ".bag"));
        read[t] += static_cast<int>(reader.read({}, 4).rc_out.size());
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(read, std::vector<int>(4, 50));
}

TEST_F(FlightBagReader, RefusesAMalformedMessage) {
  {
    rosbag::Bag bag(file("short_battery.bag"), rosbag::bagmode::Write);
    bag.write(pe::kRcOutTopic, kStart, pe::encodeRcOut(rcOutMessage({1500, 1500, 1500, 1500})));
    // The battery's type and md5sum over three bytes: a header alone needs twelve.
    std::vector<std::uint8_t> bytes = {1, 2, 3};
    topic_tools::ShapeShifter shifter;
    shifter.morph(ros::message_traits::MD5Sum<sensor_msgs::BatteryState>::value(), "sensor_msgs/BatteryState",
                  ros::message_traits::Definition<sensor_msgs::BatteryState>::value(), "0");
    ros::serialization::IStream stream(bytes.data(), bytes.size());
    shifter.read(stream);
    bag.write(pe::kBatteryTopic, kStart + ros::Duration(1.5), shifter);
  }
  EXPECT_EQ(refusal(file("short_battery.bag")),
            file("short_battery.bag") + ": /mavros/battery: at 1.500 s: malformed sensor_msgs/BatteryState: Buffer Overrun");
}

TEST_F(FlightBagReader, RefusesABatteryArrayLongerThanItsRecordBeforeAllocatingIt) {
  // A damaged cell_voltage length of 2^29: roscpp would resize the array to 2 GB before reading it.
  sensor_msgs::BatteryState battery;
  battery.header.frame_id = "bat";
  battery.voltage = 12.0f;
  std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(battery));
  ros::serialization::OStream out(bytes.data(), bytes.size());
  ros::serialization::serialize(out, battery);
  const std::uint32_t huge = 1u << 29;
  std::memcpy(bytes.data() + 12 + 4 + 3 + 7 * 4 + 4, &huge, 4);
  {
    rosbag::Bag bag(file("huge_cells.bag"), rosbag::bagmode::Write);
    bag.write(pe::kRcOutTopic, kStart, pe::encodeRcOut(rcOutMessage({1500, 1500, 1500, 1500})));
    topic_tools::ShapeShifter shifter;
    shifter.morph(ros::message_traits::MD5Sum<sensor_msgs::BatteryState>::value(), "sensor_msgs/BatteryState",
                  ros::message_traits::Definition<sensor_msgs::BatteryState>::value(), "0");
    ros::serialization::IStream stream(bytes.data(), bytes.size());
    shifter.read(stream);
    bag.write(pe::kBatteryTopic, kStart + ros::Duration(0.5), shifter);
  }
  EXPECT_EQ(refusal(file("huge_cells.bag")),
            file("huge_cells.bag") + ": /mavros/battery: at 0.500 s: malformed sensor_msgs/BatteryState: cell_voltage "
                                     "declares 536870912 elements, the 12 bytes left hold 3");
}

// A recording never closed (the recorder killed) has no index: rosbag refuses it whole, and the
// line names the remedy.
TEST_F(FlightBagReader, RefusesABagNeverClosedNamingTheRemedy) {
  writeMinimalBag(file("good.bag"));
  std::ifstream in(file("good.bag"), std::ios::binary);
  std::string bag((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = fieldValueAt(bag, "index_pos", 8);
  bag.replace(at, 8, std::string(8, '\0'));  // as rosbag record leaves it until it closes the bag
  std::ofstream(file("active.bag"), std::ios::binary) << bag;
  EXPECT_EQ(refusal(file("active.bag")), file("active.bag") +
                                             ": not a readable bag: Bag unindexed (a recording never closed); "
                                             "`rosbag reindex` indexes it");
}

// A chunk whose compressed data is corrupt ends the flight there: the messages of the chunks
// before it are read, and refusal() says where, as for a damaged ULog.
TEST_F(FlightBagReader, ReadsABagUpToAChunkItCannotRead) {
  {
    rosbag::Bag bag(file("chunks.bag"), rosbag::bagmode::Write);
    bag.setCompression(rosbag::compression::BZ2);
    bag.setChunkThreshold(4096);
    for (int k = 0; k < 400; ++k) {
      const ros::Time stamp = kStart + ros::Duration(0.1 * k);
      bag.write(pe::kRcOutTopic, stamp, pe::encodeRcOut(rcOutMessage({1500, 1500, 1500, 1500})));
      bag.write(pe::kBatteryTopic, stamp, battery(12.0 - 0.001 * k));
    }
  }
  std::ifstream in(file("chunks.bag"), std::ios::binary);
  std::string bag((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The middle of the file lies inside a chunk's compressed data.
  bag.replace(bag.size() / 2, 64, std::string(64, '\xff'));
  std::ofstream(file("corrupt.bag"), std::ios::binary) << bag;
  const pe::FlightBagReader reader(file("corrupt.bag"));
  const pe::FlightStreams streams = reader.read(pe::FlightBagTopics{}, 4);
  ASSERT_FALSE(streams.battery.empty());
  EXPECT_LT(streams.battery.back().time_s, 39.9) << "the messages after the chunk are not read";
  EXPECT_GT(streams.battery.back().time_s, 1.0) << "the chunks before it are";
  EXPECT_EQ(reader.refusal().rfind(file("corrupt.bag") + ": reading failed after ", 0), 0u) << reader.refusal();
  std::cout << "  " << reader.refusal() << "\n";
  EXPECT_EQ(pe::FlightBagReader(file("chunks.bag")).refusal(), "");
  // The first chunk's compressed data (bzip2's "BZh" after the bag header) corrupt: nothing can be
  // read, and the bag is refused.
  std::string first = bag;
  const std::size_t chunk = first.find("BZh", 4096);
  ASSERT_NE(chunk, std::string::npos);
  first.replace(chunk + 10, 32, std::string(32, '\xff'));
  std::ofstream(file("first.bag"), std::ios::binary) << first;
  EXPECT_EQ(refusal(file("first.bag")).rfind(file("first.bag") + ": reading failed after 0.000 s: ", 0), 0u)
      << refusal(file("first.bag"));
}
