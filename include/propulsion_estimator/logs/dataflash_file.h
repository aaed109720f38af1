#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace propulsion_estimator {
namespace dataflash {

/// @file
/// ArduPilot's DataFlash binary log (.bin): every message is 0xA3 0x95, a type id and the fields
/// its FMT message describes (format characters, comma-separated labels). Parsed from its bytes,
/// located, not yet decoded; a truncated or corrupt file keeps what came before its first bad
/// message, and says where it broke.

/// The bytes a log starts with: the header of the FMT message that defines FMT (type 128, 89 bytes).
extern const char kMagic[6];  // 5 bytes and a NUL

/// A column: where it lies in the message and its format character.
struct Column {
  std::size_t offset = 0;  ///< from the message's start, header included
  char format = 'f';       ///< the FMT message's format character
};

/// A message type as its FMT message defines it.
struct Type {
  std::string name;              ///< "RCOU"
  std::size_t length = 0;        ///< bytes, header included
  std::string format;            ///< "QHHHH..."
  std::vector<std::string> labels;  ///< the column names
  std::vector<Column> columns;   ///< one per label
};

/// A message, located in the file.
struct Message {
  std::uint8_t type = 0;   ///< its Type's id
  std::size_t offset = 0;  ///< of its header
};

/// A parsed DataFlash log. The bytes are kept: messages point into them.
class File {
 public:
  /// Parses `bytes`; `source` names the file in messages. Throws DataError "<source>: not a
  /// DataFlash log (...)" when it does not start with kMagic; a file that breaks later is kept up to
  /// there, with refusal() saying where.
  File(std::string bytes, std::string source);

  const std::string& source() const { return source_; }  ///< the file, for messages
  /// "" for a file read to its end; else "<source>: at byte <offset>: <message>: <problem>".
  const std::string& refusal() const { return refusal_; }
  const std::map<std::uint8_t, Type>& types() const { return types_; }  ///< by id
  const std::vector<Message>& messages() const { return messages_; }  ///< in the file's order

  /// The type id named `name` ("BAT"), or nothing.
  std::optional<std::uint8_t> typeNamed(const std::string& name) const;
  /// The column `label` of type `type`, or nothing (columns are found by label).
  std::optional<Column> column(std::uint8_t type, const std::string& label) const;
  /// The value at `column` of `message`, scaled as its format character says (c, C, e, E: x0.01;
  /// L: x1e-7); text columns give NaN.
  double value(const Message& message, const Column& column) const;

 private:
  void parseMessages();
  bool parseFormat(std::size_t at, std::string* problem);

  std::string bytes_;
  std::string source_;
  std::string refusal_;
  std::map<std::uint8_t, Type> types_;
  std::vector<Message> messages_;
};

/// The bytes of a column of format character `format`, or 0 for a character DataFlash does not have.
std::size_t columnSize(char format);

}  // namespace dataflash
}  // namespace propulsion_estimator
