#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <std_msgs/Header.h>
#include <topic_tools/shape_shifter.h>

namespace propulsion_estimator {

/// mavros_msgs/RCOut without mavros_msgs (Debian does not package it): the type is received as a
/// topic_tools::ShapeShifter, checked against this name and md5sum, and decoded by hand; the
/// simulator writes it the same way.
constexpr const char* kRcOutDataType = "mavros_msgs/RCOut";
constexpr const char* kRcOutMd5Sum = "52cacf104bab5ae3b103cfe176590713";  ///< of kRcOutDataType
/// Full definition as rosbag and rostopic expect it (RCOut.msg followed by std_msgs/Header).
const std::string& rcOutDefinition();

/// A decoded mavros_msgs/RCOut: its header and the pulse widths in us, one per output channel.
struct RcOutMessage {
  std_msgs::Header header;  ///< stamp and frame
  std::vector<std::uint16_t> channels;  ///< pulse widths, us, one per output channel
};

/// Decoder of mavros_msgs/RCOut. decode() decodes into `out`, reusing its and `buffer`'s storage
/// (no allocation once they are large enough). Returns false with a one-line reason for another
/// type or a malformed payload (cut short, or with bytes after its channels). Storage that one
/// message grew beyond kMaxKeptBytes is released: the buffer after that message, `out`'s channels
/// and frame_id at the next decode().
class RcOutDecoder {
 public:
  /// Far above any real RCOut (a few dozen bytes); a larger buffer is not kept between messages.
  static constexpr std::size_t kMaxKeptBytes = 64 * 1024;

  /// Decodes `message` into `out`; false with a one-line reason in `error` for another type or a
  /// malformed payload.
  bool decode(const topic_tools::ShapeShifter& message, RcOutMessage* out, std::string* error);
  /// Bytes of serialization buffer kept for the next message.
  std::size_t keptBytes() const { return buffer_.capacity(); }
  /// The serialized message alone, for a reader that has checked the type itself (a bag's
  /// connection): false with a one-line reason for a malformed payload.
  static bool decodePayload(const std::uint8_t* data, std::uint32_t size, RcOutMessage* out, std::string* error);

 private:
  std::vector<std::uint8_t> buffer_;
};

/// A ShapeShifter carrying `message` as mavros_msgs/RCOut, for publishing and bag writing.
topic_tools::ShapeShifter encodeRcOut(const RcOutMessage& message);

}  // namespace propulsion_estimator
