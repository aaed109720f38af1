#include <gtest/gtest.h>
#include <std_msgs/Float64.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "propulsion_estimator/codecs/esc_telemetry_codec.h"
#include "propulsion_estimator/codecs/rcout_codec.h"

namespace pe = propulsion_estimator;

namespace {

pe::EscTelemetry fourEscs() {
  pe::EscTelemetry message;
  message.stamp_s = 1600000012.5;
  for (int i = 0; i < 4; ++i) {
    message.escs.push_back({1600000012.25, 6000.0 + 10 * i, 4.5 + 0.25 * i, 15.75, 41.0, 100 + i});
  }
  return message;
}

// The md5sum ROS computes for `type` from its full definition: genpy, as rospy and rostopic do.
std::string rosMd5Sum(const std::string& type, const std::string& definition) {
  char path[] = "/tmp/pe_definition_XXXXXX";
  const int fd = mkstemp(path);
  if (fd < 0) return "mkstemp failed";
  std::ofstream(path) << definition;
  const std::string command = "/usr/bin/python3 -c \"import genpy.dynamic,sys; print(genpy.dynamic.generate_dynamic('" +
                              type + "', open('" + path + "').read())['" + type + "']._md5sum)\" 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::array<char, 256> line{};
  std::string out;
  while (pipe && fgets(line.data(), line.size(), pipe.get())) out += line.data();
  pipe.reset();
  std::remove(path);
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

}  // namespace

// The md5sums are those of mavros_msgs 1.x and 2.x (the .msg files agree), and ROS derives the same
// from the definitions written into bags: rostopic echo and rospy then accept them.
TEST(EscTelemetryCodec, TheMd5SumsAreThoseRosDerivesFromTheDefinitions) {
  EXPECT_STREQ(pe::kEscTelemetryMd5Sum, "7b1fb252ca6aa175fe8dd23d029b3362");
  EXPECT_STREQ(pe::kEscStatusMd5Sum, "145d49eaf5cfecbdfd50ae4a22fe82d4");
  EXPECT_EQ(rosMd5Sum("mavros_msgs/ESCTelemetry", pe::escTelemetryDefinition()), pe::kEscTelemetryMd5Sum);
  EXPECT_EQ(rosMd5Sum("mavros_msgs/ESCStatus", pe::escStatusDefinition()), pe::kEscStatusMd5Sum);
  EXPECT_EQ(rosMd5Sum("mavros_msgs/RCOut", pe::rcOutDefinition()), pe::kRcOutMd5Sum);
}

TEST(EscTelemetryCodec, RoundTripsBothTypes) {
  for (bool px4 : {true, false}) {
    const topic_tools::ShapeShifter shifter = pe::encodeEscTelemetry(fourEscs(), px4);
    EXPECT_EQ(shifter.getDataType(), px4 ? "mavros_msgs/ESCStatus" : "mavros_msgs/ESCTelemetry");
    pe::EscTelemetryDecoder decoder;
    pe::EscTelemetry received;
    std::string error;
    ASSERT_TRUE(decoder.decode(shifter, &received, &error)) << error;
    EXPECT_DOUBLE_EQ(received.stamp_s, 1600000012.5);
    ASSERT_EQ(received.escs.size(), 4u);
    const pe::EscReport& esc = received.escs[3];
    EXPECT_DOUBLE_EQ(esc.stamp_s, 1600000012.25);
    EXPECT_EQ(esc.rpm, 6030.0);
    EXPECT_FLOAT_EQ(esc.current_a, 5.25);
    EXPECT_FLOAT_EQ(esc.voltage_v, 15.75);
    if (px4) {
      EXPECT_TRUE(std::isnan(esc.temperature_c));
      EXPECT_EQ(esc.count, -1);
    } else {
      EXPECT_EQ(esc.temperature_c, 41.0);
      EXPECT_EQ(esc.count, 103);
    }
  }
}

TEST(EscTelemetryCodec, RefusesAnotherTypeAndMalformedPayloads) {
  std_msgs::Float64 value;
  topic_tools::ShapeShifter other;
  other.morph(ros::message_traits::md5sum(value), ros::message_traits::datatype(value),
              ros::message_traits::definition(value), "0");
  pe::EscTelemetryDecoder decoder;
  pe::EscTelemetry out;
  std::string error;
  EXPECT_FALSE(decoder.decode(other, &out, &error));
  EXPECT_EQ(error,
            "expected mavros_msgs/ESCTelemetry (md5sum 7b1fb252ca6aa175fe8dd23d029b3362) or mavros_msgs/ESCStatus "
            "(md5sum 145d49eaf5cfecbdfd50ae4a22fe82d4), got std_msgs/Float64 (md5sum fdb28210bfa9d7c91146260178d9a584)");

  // A header (12 + 4 bytes of an empty frame) and an item count far beyond the bytes.
  std::vector<std::uint8_t> bytes(20, 0);
  bytes[16] = 200;
  EXPECT_FALSE(pe::EscTelemetryDecoder::decodePayload("mavros_msgs/ESCStatus", bytes.data(), 20, &out, &error));
  EXPECT_EQ(error, "malformed mavros_msgs/ESCStatus: 200 items announced, 0 bytes left");
  EXPECT_FALSE(pe::EscTelemetryDecoder::decodePayload("mavros_msgs/ESCStatus", nullptr, 0, &out, &error));
  EXPECT_EQ(error, "malformed mavros_msgs/ESCStatus: empty message");
  // Bytes after the items.
  bytes.assign(24, 0);
  EXPECT_FALSE(pe::EscTelemetryDecoder::decodePayload("mavros_msgs/ESCTelemetry", bytes.data(), 24, &out, &error));
  EXPECT_EQ(error, "malformed mavros_msgs/ESCTelemetry: 4 bytes after the 0 items");
  // A negative rpm.
  pe::EscTelemetry negative = fourEscs();
  negative.escs[1].rpm = -5.0;
  EXPECT_FALSE(decoder.decode(pe::encodeEscTelemetry(negative, true), &out, &error));
  EXPECT_EQ(error, "malformed mavros_msgs/ESCStatus: item 1: rpm -5 is negative");
}
