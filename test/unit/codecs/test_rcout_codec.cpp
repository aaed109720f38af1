#include <gtest/gtest.h>
#include <std_msgs/Float64.h>

#include "propulsion_estimator/codecs/rcout_codec.h"

namespace pe = propulsion_estimator;

TEST(RcOutCodec, RoundTripsHeaderAndChannels) {
  pe::RcOutMessage sent;
  sent.header.seq = 7;
  sent.header.stamp = ros::Time(12, 500);
  sent.header.frame_id = "base_link";
  sent.channels = {1500, 1510, 1490, 1505, 900, 900, 0, 0};
  const topic_tools::ShapeShifter shifter = pe::encodeRcOut(sent);
  EXPECT_EQ(shifter.getDataType(), "mavros_msgs/RCOut");
  EXPECT_EQ(shifter.getMD5Sum(), "52cacf104bab5ae3b103cfe176590713");

  pe::RcOutDecoder decoder;
  pe::RcOutMessage received;
  std::string error;
  ASSERT_TRUE(decoder.decode(shifter, &received, &error)) << error;
  EXPECT_EQ(received.header.stamp, sent.header.stamp);
  EXPECT_EQ(received.header.frame_id, "base_link");
  EXPECT_EQ(received.channels, sent.channels);
}

TEST(RcOutCodec, ReleasesWhatAnOversizedMessageGrew) {
  pe::RcOutMessage big;
  big.header.frame_id = std::string(1 << 20, 'f');
  big.channels.assign(200000, 1500);
  pe::RcOutMessage small;
  small.header.frame_id = "base_link";
  small.channels = {1500, 1510, 1490, 1505};
  pe::RcOutDecoder decoder;
  pe::RcOutMessage received;
  std::string error;

  ASSERT_TRUE(decoder.decode(pe::encodeRcOut(small), &received, &error)) << error;
  const std::size_t small_bytes = decoder.keptBytes();
  EXPECT_GT(small_bytes, 0u);  // a normal message's buffer is kept for the next one

  ASSERT_TRUE(decoder.decode(pe::encodeRcOut(big), &received, &error)) << error;
  EXPECT_EQ(received.header.frame_id, big.header.frame_id);
  EXPECT_EQ(received.channels, big.channels);
  EXPECT_EQ(decoder.keptBytes(), 0u);  // released after the message

  ASSERT_TRUE(decoder.decode(pe::encodeRcOut(small), &received, &error)) << error;
  EXPECT_EQ(received.header.frame_id, "base_link");
  EXPECT_EQ(received.channels, small.channels);
  EXPECT_EQ(decoder.keptBytes(), small_bytes);
  EXPECT_LE(received.header.frame_id.capacity(), pe::RcOutDecoder::kMaxKeptBytes);
  EXPECT_LE(received.channels.capacity() * sizeof(std::uint16_t), pe::RcOutDecoder::kMaxKeptBytes);
}

TEST(RcOutCodec, DefinitionEndsWithTheStdMsgsHeader) {
  const std::string& definition = pe::rcOutDefinition();
  EXPECT_EQ(definition.rfind("# RAW Servo out state\n\nstd_msgs/Header header\nuint16[] channels\n\n====", 0), 0u);
  EXPECT_NE(definition.find("\nMSG: std_msgs/Header\n"), std::string::npos);
  EXPECT_NE(definition.find("string frame_id"), std::string::npos);
}

TEST(RcOutCodec, RefusesOtherTypes) {
  topic_tools::ShapeShifter shifter;
  shifter.morph(ros::message_traits::MD5Sum<std_msgs::Float64>::value(), "std_msgs/Float64",
                ros::message_traits::Definition<std_msgs::Float64>::value(), "0");
  pe::RcOutDecoder decoder;
  pe::RcOutMessage received;
  std::string error;
  EXPECT_FALSE(decoder.decode(shifter, &received, &error));
  EXPECT_EQ(error,
            "expected mavros_msgs/RCOut (md5sum 52cacf104bab5ae3b103cfe176590713), got std_msgs/Float64 (md5sum "
            "fdb28210bfa9d7c91146260178d9a584)");
}

TEST(RcOutCodec, RefusesATruncatedPayload) {
  pe::RcOutMessage sent;
  sent.channels = {1500, 1500, 1500, 1500};
  std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(sent.header) + 4 + 8);
  ros::serialization::OStream writer(bytes.data(), bytes.size());
  ros::serialization::serialize(writer, sent.header);
  ros::serialization::serialize(writer, std::uint32_t{1000});  // claims 1000 channels
  topic_tools::ShapeShifter shifter;
  shifter.morph(pe::kRcOutMd5Sum, pe::kRcOutDataType, pe::rcOutDefinition(), "0");
  ros::serialization::IStream reader(bytes.data(), bytes.size());
  shifter.read(reader);
  pe::RcOutDecoder decoder;
  pe::RcOutMessage received;
  std::string error;
  EXPECT_FALSE(decoder.decode(shifter, &received, &error));
  EXPECT_EQ(error, "malformed mavros_msgs/RCOut: 1000 channels announced, 8 bytes left");
}


TEST(RcOutCodec, DecodesAPayloadWhoseTypeWasCheckedElsewhere) {
  pe::RcOutMessage sent;
  sent.header.stamp = ros::Time(3, 0);
  sent.channels = {1600, 1610, 1590, 1605};
  std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(sent.header) + 4 + 8);
  ros::serialization::OStream writer(bytes.data(), bytes.size());
  ros::serialization::serialize(writer, sent.header);
  ros::serialization::serialize(writer, sent.channels);
  pe::RcOutMessage received;
  std::string error;
  ASSERT_TRUE(pe::RcOutDecoder::decodePayload(bytes.data(), bytes.size(), &received, &error)) << error;
  EXPECT_EQ(received.header.stamp, sent.header.stamp);
  EXPECT_EQ(received.channels, sent.channels);
  // Cut inside the channels: refused, not read past the end.
  EXPECT_FALSE(pe::RcOutDecoder::decodePayload(bytes.data(), bytes.size() - 3, &received, &error));
  EXPECT_EQ(error, "malformed mavros_msgs/RCOut: 4 channels announced, 5 bytes left");
}

TEST(RcOutCodec, RefusesBytesAfterTheChannels) {
  pe::RcOutMessage sent;
  sent.header.stamp = ros::Time(3, 0);
  sent.channels = {1600, 1610, 1590, 1605};
  std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(sent.header) + 4 + 8 + 3);
  ros::serialization::OStream writer(bytes.data(), bytes.size());
  ros::serialization::serialize(writer, sent.header);
  ros::serialization::serialize(writer, sent.channels);
  pe::RcOutMessage received;
  std::string error;
  EXPECT_FALSE(pe::RcOutDecoder::decodePayload(bytes.data(), bytes.size(), &received, &error));
  EXPECT_EQ(error, "malformed mavros_msgs/RCOut: 3 bytes after the 4 channels");
}

// Found by fuzz_rcout: an empty message was read from a null pointer (undefined behaviour).
TEST(RcOutCodec, RefusesAnEmptyMessage) {
  topic_tools::ShapeShifter shifter;
  shifter.morph(pe::kRcOutMd5Sum, pe::kRcOutDataType, pe::rcOutDefinition(), "0");
  pe::RcOutDecoder decoder;
  pe::RcOutMessage received;
  std::string error;
  EXPECT_FALSE(decoder.decode(shifter, &received, &error));
  EXPECT_EQ(error, "malformed mavros_msgs/RCOut: empty message");
  error.clear();
  EXPECT_FALSE(pe::RcOutDecoder::decodePayload(nullptr, 0, &received, &error));
  EXPECT_EQ(error, "malformed mavros_msgs/RCOut: empty message");
}
