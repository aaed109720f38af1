#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace propulsion_estimator {
namespace ulog {

/// @file
/// PX4's ULog file (docs.px4.io, "ULog File Format"), parsed from its bytes: the definitions
/// (formats with nested types, info), the subscriptions (multi-instance topics) and the data
/// messages, located, not yet decoded. Appended data (the B message's offsets) is followed;
/// dropouts are counted; a truncated or corrupt file keeps what came before its first bad
/// message, and says where it broke.

/// The bytes every ULog starts with: "ULog", 0x01, 0x12, 0x35.
extern const char kMagic[8];  // 7 bytes and a NUL

/// A field's primitive type.
enum class Primitive { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kInt64, kUint64, kFloat, kDouble, kBool, kChar };

/// A field of a format: a primitive or another format (nested), an array when `count` > 0.
struct Field {
  std::string name;                    ///< the field's name in its format
  std::optional<Primitive> primitive;  ///< empty for a nested format
  std::string nested;                  ///< the nested format's name
  int count = 0;                       ///< array length; 0 for a scalar
  std::size_t offset = 0;              ///< bytes from the message's start
  std::size_t size = 0;                ///< bytes, all elements
};

/// A message format ("F"): its fields in order, and its size in bytes.
struct Format {
  std::string name;          ///< "battery_status"
  std::vector<Field> fields;  ///< in the message's order
  std::size_t size = 0;      ///< bytes of a message of this format
};

/// Where a primitive value lies in a message: "voltage_v", "q[2]", "esc[1].esc_temperature".
struct Locator {
  std::size_t offset = 0;                   ///< bytes from the message's first field
  Primitive primitive = Primitive::kFloat;  ///< the value's type
};

/// An "A" message: topic `name`, instance `multi_id`, data messages tagged `msg_id`.
struct Subscription {
  std::string name;  ///< the topic (its format's name)
  int multi_id = 0;  ///< the instance, 0 for the first
};

/// A data message ("D"), located in the file's bytes.
struct DataMessage {
  std::uint16_t msg_id = 0;  ///< the subscription it belongs to
  std::size_t offset = 0;  ///< of its payload after msg_id: the message's first field
  std::size_t size = 0;    ///< bytes of its payload
};

/// A parsed ULog. The bytes are kept: data messages point into them.
class File {
 public:
  /// Parses `bytes`; `source` names the file in messages. A file that is not a ULog (wrong magic,
  /// shorter than the header, an incompatible flag it does not know) throws DataError
  /// "<source>: <problem>"; a file that breaks later is kept up to there, with refusal() saying
  /// where.
  File(std::string bytes, std::string source);

  const std::string& source() const { return source_; }  ///< the file, for messages
  /// "" for a file read to its end; else "<source>: at byte <offset>: <message>: <problem>".
  const std::string& refusal() const { return refusal_; }
  /// The logger's dropouts ("O"): how many, and their total in ms.
  int dropouts() const { return dropouts_; }
  int dropoutMs() const { return dropout_ms_; }  ///< total time lost to dropouts, ms
  /// Info messages ("I", and the first part of "M"): key without its type -> raw value bytes.
  const std::map<std::string, std::string>& info() const { return info_; }
  /// The info `key` as text (a char[] value), or "" when absent or of another type.
  std::string infoText(const std::string& key) const;

  const std::map<std::string, Format>& formats() const { return formats_; }  ///< by name
  /// The subscriptions by msg_id.
  const std::map<std::uint16_t, Subscription>& subscriptions() const { return subscriptions_; }
  const std::vector<DataMessage>& data() const { return data_; }  ///< in the file's order

  /// Where `path` lies in format `format` ("q[0]", "esc[3].esc_temperature"), or nothing when the
  /// format has no such field (fields are found by name, never by a guessed offset).
  std::optional<Locator> locate(const std::string& format, const std::string& path) const;
  /// The value at `locator` in data message `message`, as a double; NaN when the message is too
  /// short to hold it (PX4 may cut a message's trailing padding, never a field).
  double value(const DataMessage& message, const Locator& locator) const;
  /// The message's timestamp (its first field, uint64 us).
  std::uint64_t timestampUs(const DataMessage& message) const;

 private:
  void parseHeader();
  void parseMessages();
  bool parseMessage(char type, std::size_t at, std::size_t size, std::string* problem);
  bool parseFormat(const std::string& text, std::string* problem);
  bool resolve(Format* format, std::vector<std::string>* resolving, std::string* problem);

  std::string bytes_;
  std::string source_;
  std::string refusal_;
  std::uint64_t appended_offset_ = 0;
  int dropouts_ = 0;
  int dropout_ms_ = 0;
  std::map<std::string, std::string> info_;
  std::map<std::string, Format> formats_;
  std::map<std::uint16_t, Subscription> subscriptions_;
  std::vector<DataMessage> data_;
};

/// The size in bytes of `primitive`.
std::size_t sizeOf(Primitive primitive);
/// The primitive named `name` in a format ("uint16_t", "float", ...), or nothing.
std::optional<Primitive> primitiveNamed(const std::string& name);

}  // namespace ulog
}  // namespace propulsion_estimator
