#pragma once

#include <cstdint>
#include <string>

#include "propulsion_estimator/logs/binary_payload.h"

namespace propulsion_estimator {
namespace ulog {

/// A data message's bytes, as its format lays them out.
using Payload = BinaryPayload;

/// Writes a ULog in memory, message by message, in the order called: the header, then
/// definitions (flag bits, formats, info) before data (subscriptions, data, dropouts). The
/// caller keeps the format's rules (definitions first, a data message's payload laid out as its
/// format says); the writer only frames the messages.
class Writer {
 public:
  /// The header, with the log's start in microseconds since boot.
  explicit Writer(std::uint64_t start_us);

  /// The flag bits message (first after the header, if at all): with `appended_offset` > 0 the
  /// DATA_APPENDED incompatible flag and that offset.
  void flagBits(std::uint64_t appended_offset = 0);
  /// A format: "name:type field;type field;..." (docs.px4.io, ULog File Format).
  void format(const std::string& definition);
  /// An info message: `key` as "type name" ("char[5] sys_name"), `value` its bytes.
  void info(const std::string& key, const std::string& value);
  /// Subscribes `msg_id` to topic `name`, instance `multi_id`.
  void subscribe(std::uint16_t msg_id, const std::string& name, std::uint8_t multi_id = 0);
  /// A data message of `msg_id`; `payload` starts with the uint64 timestamp.
  void data(std::uint16_t msg_id, const Payload& payload);
  /// A dropout of `duration_ms`.
  void dropout(std::uint16_t duration_ms);

  /// The file so far.
  const std::string& bytes() const { return bytes_; }
  /// Writes bytes() to `path`; InputError "<path>: cannot open for writing" / "cannot write".
  void save(const std::string& path) const;

 private:
  void message(char type, const std::string& payload);

  std::string bytes_;
};

}  // namespace ulog
}  // namespace propulsion_estimator
