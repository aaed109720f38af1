#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "propulsion_estimator/logs/binary_payload.h"

namespace propulsion_estimator {
namespace crazyflie {

/// Writes a Crazyflie uSD log (version 2) in memory: the event types, then the records, then the
/// CRC-32 of all before it. The caller lays each record's values out as its variables' type
/// characters say (a float16 'e' as its uint16 bits).
class Writer {
 public:
  /// Defines event type `id` named `name` with `variables` as the header spells them
  /// ("pwm.m1_pwm(I)"); std::invalid_argument for an id defined twice, a variable not of the form
  /// group.name(T) with a type character the format has, or a definition after the first record.
  void define(std::uint16_t id, const std::string& name, const std::vector<std::string>& variables);
  /// A record of event `id` at `timestamp_us` (us since boot) with `values`; std::invalid_argument
  /// for an id not defined or values whose size is not the event's.
  void write(std::uint16_t id, std::uint64_t timestamp_us, const BinaryPayload& values);

  /// The whole log: header, records and CRC.
  std::string bytes() const;
  /// Writes bytes() to `path`; InputError "<path>: cannot open for writing" / "cannot write".
  void save(const std::string& path) const;

 private:
  struct Defined {
    std::uint16_t id;
    std::size_t record_size;
  };

  std::vector<Defined> defined_;
  std::string types_;
  std::string records_;
};

}  // namespace crazyflie
}  // namespace propulsion_estimator
