#include "propulsion_estimator/codecs/esc_telemetry_codec.h"

#include <ros/serialization.h>
#include <std_msgs/Header.h>

#include <cmath>

namespace propulsion_estimator {
namespace {

namespace ser = ros::serialization;

// The message files of mavros_msgs (mavros 1.x master and 2.x ros2 agree), verbatim.
constexpr const char* kEscTelemetryText =
    "# APM ESC Telemetry as returned by BLHeli\n#\n# See:\n"
    "# https://mavlink.io/en/messages/ardupilotmega.html#ESC_TELEMETRY_1_TO_4\n"
    "# https://mavlink.io/en/messages/ardupilotmega.html#ESC_TELEMETRY_5_TO_8\n"
    "# https://mavlink.io/en/messages/ardupilotmega.html#ESC_TELEMETRY_9_TO_12\n\n";
constexpr const char* kEscTelemetryItemFields =
    "std_msgs/Header header\n\n"
    "float32 temperature     # deg C\n"
    "float32 voltage         # V\n"
    "float32 current         # A\n"
    "float32 totalcurrent    # Ah\n"
    "int32 rpm               # 1/min\n"
    "uint16 count            # count of telemetry packets\n";
constexpr const char* kEscStatusText =
    "# ESCStatus.msg\n#\n#\n# See mavlink message documentation here:\n"
    "# https://mavlink.io/en/messages/common.html#ESC_STATUS\n\n";
constexpr const char* kEscStatusItemText =
    "# ESCStatusItem.msg\n#\n#\n# See mavlink message documentation here:\n"
    "# https://mavlink.io/en/messages/common.html#ESC_STATUS\n\n"
    "std_msgs/Header header\n\n"
    "int32 rpm\nfloat32 voltage\nfloat32 current\n";

// genmsg's full text: the message, then each type it uses in the order it first uses them.
std::string fullText(const std::string& text, const std::string& item_type, const std::string& item_text) {
  const std::string rule = "\n" + std::string(80, '=') + "\n";
  return text + rule + "MSG: std_msgs/Header\n" + ros::message_traits::Definition<std_msgs::Header>::value() + rule +
         "MSG: " + item_type + "\n" + item_text;
}

void readHeader(ser::IStream& reader, double* stamp_s) {
  std::uint32_t seq = 0, sec = 0, nsec = 0, frame_length = 0;
  ser::deserialize(reader, seq);
  ser::deserialize(reader, sec);
  ser::deserialize(reader, nsec);
  ser::deserialize(reader, frame_length);
  reader.advance(frame_length);
  *stamp_s = ros::Time(sec, nsec).toSec();
}

bool readItem(ser::IStream& reader, bool px4, EscReport* item, std::string* error) {
  readHeader(reader, &item->stamp_s);
  float voltage = 0.0f, current = 0.0f;
  std::int32_t rpm = 0;
  if (px4) {
    ser::deserialize(reader, rpm);
    ser::deserialize(reader, voltage);
    ser::deserialize(reader, current);
    item->temperature_c = std::nan("");
    item->count = -1;
  } else {
    float temperature = 0.0f, total = 0.0f;
    std::uint16_t count = 0;
    ser::deserialize(reader, temperature);
    ser::deserialize(reader, voltage);
    ser::deserialize(reader, current);
    ser::deserialize(reader, total);
    ser::deserialize(reader, rpm);
    ser::deserialize(reader, count);
    item->temperature_c = temperature;
    item->count = count;
  }
  // ESCs report the speed's magnitude; a negative one is a reversed motor or garbage, not a speed.
  if (rpm < 0) {
    *error = "rpm " + std::to_string(rpm) + " is negative";
    return false;
  }
  item->rpm = rpm;
  item->voltage_v = voltage;
  item->current_a = current;
  return true;
}

}  // namespace

const std::string& escTelemetryDefinition() {
  static const std::string definition =
      fullText(std::string(kEscTelemetryText) + "std_msgs/Header header\n\nmavros_msgs/ESCTelemetryItem[] esc_telemetry\n",
               "mavros_msgs/ESCTelemetryItem", std::string(kEscTelemetryText) + kEscTelemetryItemFields);
  return definition;
}

const std::string& escStatusDefinition() {
  static const std::string definition =
      fullText(std::string(kEscStatusText) + "std_msgs/Header header\n\nmavros_msgs/ESCStatusItem[] esc_status\n",
               "mavros_msgs/ESCStatusItem", kEscStatusItemText);
  return definition;
}

bool EscTelemetryDecoder::decode(const topic_tools::ShapeShifter& message, EscTelemetry* out, std::string* error) {
  const std::string& type = message.getDataType();
  const bool telemetry = type == kEscTelemetryDataType && message.getMD5Sum() == kEscTelemetryMd5Sum;
  const bool status = type == kEscStatusDataType && message.getMD5Sum() == kEscStatusMd5Sum;
  if (!telemetry && !status) {
    *error = "expected " + std::string(kEscTelemetryDataType) + " (md5sum " + kEscTelemetryMd5Sum + ") or " +
             kEscStatusDataType + " (md5sum " + kEscStatusMd5Sum + "), got " + type + " (md5sum " +
             message.getMD5Sum() + ")";
    return false;
  }
  const std::uint32_t size = message.size();
  if (size == 0) return decodePayload(type, nullptr, 0, out, error);
  if (buffer_.size() < size) buffer_.resize(size);
  ser::OStream writer(buffer_.data(), size);
  message.write(writer);
  return decodePayload(type, buffer_.data(), size, out, error);
}

bool EscTelemetryDecoder::decodePayload(const std::string& datatype, const std::uint8_t* data, std::uint32_t size,
                                        EscTelemetry* out, std::string* error) {
  const bool px4 = datatype == kEscStatusDataType;
  // Built only on an error path: the per-message path allocates nothing.
  const auto what = [&datatype] { return "malformed " + datatype + ": "; };
  if (size == 0) {
    *error = what() + "empty message";
    return false;
  }
  try {
    ser::IStream reader(const_cast<std::uint8_t*>(data), size);
    readHeader(reader, &out->stamp_s);
    std::uint32_t count = 0;
    ser::deserialize(reader, count);
    // Each item holds at least its header's 16 bytes and 12 of fields.
    constexpr std::uint32_t kMinItemBytes = 28;
    if (count > reader.getLength() / kMinItemBytes) {
      *error = what() + std::to_string(count) + " items announced, " + std::to_string(reader.getLength()) + " bytes left";
      return false;
    }
    out->escs.resize(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      std::string reason;
      if (!readItem(reader, px4, &out->escs[i], &reason)) {
        *error = what() + "item " + std::to_string(i) + ": " + reason;
        return false;
      }
    }
    if (reader.getLength() != 0) {
      *error = what() + std::to_string(reader.getLength()) + " bytes after the " + std::to_string(count) + " items";
      return false;
    }
  } catch (const ser::StreamOverrunException& e) {
    *error = what() + e.what();
    return false;
  }
  return true;
}

topic_tools::ShapeShifter encodeEscTelemetry(const EscTelemetry& message, bool px4) {
  const auto header = [](double stamp_s) {
    std_msgs::Header result;
    result.stamp = ros::Time(stamp_s);
    return result;
  };
  const std::uint32_t item_bytes = 16 + (px4 ? 12 : 22);  // an empty frame_id's header, then the fields
  const std::uint32_t size =
      ser::serializationLength(header(message.stamp_s)) + 4 + item_bytes * static_cast<std::uint32_t>(message.escs.size());
  std::vector<std::uint8_t> buffer(size);
  ser::OStream writer(buffer.data(), size);
  ser::serialize(writer, header(message.stamp_s));
  ser::serialize(writer, static_cast<std::uint32_t>(message.escs.size()));
  for (const EscReport& esc : message.escs) {
    ser::serialize(writer, header(esc.stamp_s));
    const auto rpm = static_cast<std::int32_t>(std::lround(esc.rpm));
    if (px4) {
      ser::serialize(writer, rpm);
      ser::serialize(writer, static_cast<float>(esc.voltage_v));
      ser::serialize(writer, static_cast<float>(esc.current_a));
    } else {
      ser::serialize(writer, static_cast<float>(esc.temperature_c));
      ser::serialize(writer, static_cast<float>(esc.voltage_v));
      ser::serialize(writer, static_cast<float>(esc.current_a));
      ser::serialize(writer, 0.0f);  // totalcurrent, Ah: not used here
      ser::serialize(writer, rpm);
      ser::serialize(writer, static_cast<std::uint16_t>(esc.count < 0 ? 0 : esc.count));
    }
  }
  topic_tools::ShapeShifter shifter;
  if (px4) {
    shifter.morph(kEscStatusMd5Sum, kEscStatusDataType, escStatusDefinition(), "0");
  } else {
    shifter.morph(kEscTelemetryMd5Sum, kEscTelemetryDataType, escTelemetryDefinition(), "0");
  }
  ser::IStream reader(buffer.data(), size);
  shifter.read(reader);
  return shifter;
}

}  // namespace propulsion_estimator
