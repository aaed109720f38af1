#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace propulsion_estimator {
namespace crazyflie {

/// @file
/// The Crazyflie uSD deck's binary event log (Bitcraze crazyflie-firmware, usddeck; "cfusdlog"),
/// version 2, little-endian: 0xBC, uint16 version, uint16 number of event types; per event type a
/// uint16 id, its NUL-terminated name and uint16 number of variables, each a NUL-terminated
/// "group.name(T)" (T a type character); then records (uint16 event id, uint64 timestamp in us
/// since boot, the event's values packed in order) up to the last 4 bytes, the CRC-32 of all before
/// them. Parsed from its bytes into columns; a truncated or corrupt file keeps the records before
/// its first bad one, and says where it broke.

/// The bytes a version-2 log starts with: 0xBC and the version, 2 (uint16).
extern const char kMagic[4];  // 3 bytes and a NUL

/// A logged variable as the header names it.
struct Variable {
  std::string name;  ///< "pwm.m1_pwm" (the header's "pwm.m1_pwm(I)" without its type)
  char type = 'f';   ///< B, H, I (uint8, 16, 32), b, h, i (int8, 16, 32), f (float32), e (float16)
};

/// An event type and its records, one column per variable.
struct Event {
  std::uint16_t id = 0;                      ///< the records' event id (fixedFrequency: 0xFFFF)
  std::string name;                          ///< "fixedFrequency"
  std::vector<Variable> variables;           ///< in the records' order
  std::size_t record_size = 0;               ///< bytes of a record's values (its 10-byte head not counted)
  std::vector<std::uint64_t> timestamp_us;   ///< per record, us since boot
  std::vector<std::vector<double>> columns;  ///< per variable, one value per record, as logged (no unit change)

  /// The column of the variable named `name`, or nothing.
  std::optional<std::size_t> column(const std::string& name) const;
};

/// A parsed uSD log.
class File {
 public:
  /// Parses `bytes`; `source` names the file in messages. Throws DataError "<source>: not a
  /// Crazyflie uSD log (...)", "<source>: Crazyflie uSD log version <v>: only version 2 is read",
  /// or "<source>: at byte <offset>: header: <problem>" for a header it cannot read (truncated, an
  /// unknown type character, an event id defined twice). A file that breaks in its records (cut by a
  /// power loss, an unknown event id, a CRC that does not match) keeps the records before, with
  /// refusal() saying where.
  File(const std::string& bytes, std::string source);

  const std::string& source() const { return source_; }  ///< the file, for messages
  /// "" for a file read to its CRC, which matched; else "<source>: at byte <offset>: <what>: <problem>".
  const std::string& refusal() const { return refusal_; }
  const std::vector<Event>& events() const { return events_; }  ///< in the header's order

  /// The event type whose records carry variable `name` (the first, if more than one), or nullptr.
  const Event* eventWith(const std::string& name) const;

 private:
  void parseHeader(const std::string& bytes, std::size_t* at);
  void parseRecords(const std::string& bytes, std::size_t at);

  std::string source_;
  std::string refusal_;
  std::vector<Event> events_;
};

/// The bytes of a value of type character `type`, or 0 for a character the format does not have.
std::size_t valueSize(char type);

/// The CRC-32 a log ends with (ISO-HDLC, as zlib's crc32) of the `size` bytes at `data`.
std::uint32_t crc32(const char* data, std::size_t size);

}  // namespace crazyflie
}  // namespace propulsion_estimator
