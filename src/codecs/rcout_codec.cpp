#include "propulsion_estimator/codecs/rcout_codec.h"

#include <ros/serialization.h>

namespace propulsion_estimator {

const std::string& rcOutDefinition() {
  static const std::string definition =
      std::string("# RAW Servo out state\n\nstd_msgs/Header header\nuint16[] channels\n\n") + std::string(80, '=') +
      "\nMSG: std_msgs/Header\n" + ros::message_traits::Definition<std_msgs::Header>::value();
  return definition;
}

bool RcOutDecoder::decode(const topic_tools::ShapeShifter& message, RcOutMessage* out, std::string* error) {
  if (message.getDataType() != kRcOutDataType || message.getMD5Sum() != kRcOutMd5Sum) {
    *error = "expected " + std::string(kRcOutDataType) + " (md5sum " + kRcOutMd5Sum + "), got " +
             message.getDataType() + " (md5sum " + message.getMD5Sum() + ")";
    return false;
  }
  // What an earlier, oversized message left in `out` (the caller has used it since).
  if (out->channels.capacity() * sizeof(std::uint16_t) > kMaxKeptBytes) std::vector<std::uint16_t>().swap(out->channels);
  if (out->header.frame_id.capacity() > kMaxKeptBytes) std::string().swap(out->header.frame_id);
  const std::uint32_t size = message.size();
  // An empty message has no buffer to write from or into (ShapeShifter::write would copy from a null pointer).
  if (size == 0) return decodePayload(nullptr, 0, out, error);
  if (buffer_.size() < size) buffer_.resize(size);
  ros::serialization::OStream writer(buffer_.data(), size);
  message.write(writer);
  const bool decoded = decodePayload(buffer_.data(), size, out, error);
  if (buffer_.capacity() > kMaxKeptBytes) std::vector<std::uint8_t>().swap(buffer_);
  return decoded;
}

bool RcOutDecoder::decodePayload(const std::uint8_t* data, std::uint32_t size, RcOutMessage* out, std::string* error) {
  // Reading would advance a null pointer (undefined behaviour) before finding the stream overrun.
  if (size == 0) {
    *error = "malformed mavros_msgs/RCOut: empty message";
    return false;
  }
  try {
    // IStream only reads, but takes a mutable pointer.
    ros::serialization::IStream reader(const_cast<std::uint8_t*>(data), size);
    // The header by hand: roscpp's string deserializer builds a temporary std::string, which
    // allocates for a frame_id longer than the small-string buffer; assign() reuses capacity.
    std_msgs::Header& header = out->header;
    ros::serialization::deserialize(reader, header.seq);
    ros::serialization::deserialize(reader, header.stamp.sec);
    ros::serialization::deserialize(reader, header.stamp.nsec);
    std::uint32_t frame_length = 0;
    ros::serialization::deserialize(reader, frame_length);
    const char* frame = reinterpret_cast<const char*>(reader.advance(frame_length));
    header.frame_id.assign(frame, frame_length);
    std::uint32_t count = 0;
    ros::serialization::deserialize(reader, count);
    if (count > reader.getLength() / sizeof(std::uint16_t)) {
      *error = "malformed mavros_msgs/RCOut: " + std::to_string(count) + " channels announced, " +
               std::to_string(reader.getLength()) + " bytes left";
      return false;
    }
    out->channels.resize(count);
    for (std::uint16_t& channel : out->channels) ros::serialization::deserialize(reader, channel);
    // Bytes after the channels: the message is not the RCOut its type says (a channel count too
    // small, or two messages run together), and its channels cannot be trusted.
    if (reader.getLength() != 0) {
      *error = "malformed mavros_msgs/RCOut: " + std::to_string(reader.getLength()) + " bytes after the " +
               std::to_string(count) + " channels";
      return false;
    }
  } catch (const ros::serialization::StreamOverrunException& e) {
    *error = std::string("malformed mavros_msgs/RCOut: ") + e.what();
    return false;
  }
  return true;
}

topic_tools::ShapeShifter encodeRcOut(const RcOutMessage& message) {
  const std::uint32_t size =
      ros::serialization::serializationLength(message.header) + 4 + 2 * static_cast<std::uint32_t>(message.channels.size());
  std::vector<std::uint8_t> buffer(size);
  ros::serialization::OStream writer(buffer.data(), size);
  ros::serialization::serialize(writer, message.header);
  ros::serialization::serialize(writer, message.channels);
  topic_tools::ShapeShifter shifter;
  shifter.morph(kRcOutMd5Sum, kRcOutDataType, rcOutDefinition(), "0");
  ros::serialization::IStream reader(buffer.data(), size);
  shifter.read(reader);
  return shifter;
}

}  // namespace propulsion_estimator
