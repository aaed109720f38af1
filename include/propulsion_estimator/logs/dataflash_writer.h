#pragma once

#include <cstdint>
#include <string>

#include "propulsion_estimator/logs/binary_payload.h"

namespace propulsion_estimator {
namespace dataflash {

/// Writes a DataFlash log in memory: the FMT message of FMT first, then each type's FMT before
/// its first message. The caller lays each payload out as its format characters say.
class Writer {
 public:
  Writer();

  /// Defines type `id` (0..127, ArduPilot's range for log messages) named `name` (up to 4
  /// characters) with `format` characters and comma-separated `labels`; std::invalid_argument
  /// for a format character DataFlash does not have or labels that do not match it.
  void define(std::uint8_t id, const std::string& name, const std::string& format, const std::string& labels);
  /// A message of type `id` with `payload` after its header.
  void write(std::uint8_t id, const BinaryPayload& payload);

  const std::string& bytes() const { return bytes_; }  ///< the log written so far
  /// Writes bytes() to `path`; InputError "<path>: cannot open for writing" / "cannot write".
  void save(const std::string& path) const;

 private:
  std::string bytes_;
};

}  // namespace dataflash
}  // namespace propulsion_estimator
