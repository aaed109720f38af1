#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "propulsion_estimator/logs/flight_log_reader.h"

namespace propulsion_estimator {

/// A flight-log format as the registry knows it: told from the file's first bytes, never from its
/// name.
struct FlightLogFormat {
  std::string name;   ///< "rosbag", for messages and the README
  std::string magic;  ///< the bytes every file of the format starts with ("#ROSBAG V2.0")
  /// Opens a file that starts with `magic`; throws as the format's reader does (InputError,
  /// DataError "<path>: ...").
  std::function<std::unique_ptr<FlightLogReader>(const std::string& path)> open;
};

/// The flight-log formats a tool reads. Each format is added once, with one line, where the tool
/// builds its registry (src/apps/flight_log_formats.cpp).
class FlightLogFormats {
 public:
  /// Adds `format`; std::invalid_argument for an empty magic or a name or magic already added.
  void add(FlightLogFormat format);

  /// Opens `path` with the format whose magic it starts with. InputError as requireRegularFile (no such file, a folder, a device)
  /// or "<path>: cannot be read"; DataError "<path>: empty: not a flight log", "<path>: a FORMAT
  /// log cut short: it ends after N bytes, within its first M ("MAGIC")", "<path>: not a
  /// flight log of a known format (rosbag, ...): it starts with "<its first bytes, escaped>"", or
  /// whatever the format's reader throws.
  std::unique_ptr<FlightLogReader> open(const std::string& path) const;

  /// The formats' names, in the order they were added.
  std::vector<std::string> names() const;

 private:
  std::vector<FlightLogFormat> formats_;
};

}  // namespace propulsion_estimator
