#pragma once

#include <map>
#include <string>

#include "propulsion_estimator/logs/flight_streams.h"

namespace propulsion_estimator {

/// What a reader is asked for, whatever the format.
struct FlightLogOptions {
  int motors = 4;  ///< motors 1..motors are the log's output channels 1..motors (1..kMaxMotors)
  /// Signal name (flightSignalNames()) -> where the format finds it, in the format's terms (a
  /// rosbag's topic); a signal not named is read from the format's usual source.
  std::map<std::string, std::string> sources;

  /// Throws ConfigError "<what>: ..." for motors outside 1..kMaxMotors or a source whose name is
  /// not a signal; `what` names the input the options came from ("--topic", a file).
  void validate(const std::string& what) const;
};

/// One flight log opened for reading, on the manifest's clock: seconds from the log's first
/// message. One implementation per format (bag/flight_bag_reader.h, ...), made by the
/// FlightLogFormats registry from the file's content. A reader may be used on any thread; two
/// readers of different files may read at once.
class FlightLogReader {
 public:
  virtual ~FlightLogReader() = default;

  /// The file, as opened.
  virtual const std::string& path() const = 0;
  /// From the first message to the last, in seconds.
  virtual double durationS() const = 0;
  /// Reads the flight's signals (times in s on the manifest's clock, values in SI units as
  /// FlightStreams says). rc_out and battery are required; an optional signal the log lacks leaves
  /// its stream empty. Throws DataError "<path>: ..." for a log the reader refuses (a required
  /// signal missing, a malformed message: the message names the place) and ConfigError for
  /// options it cannot use.
  virtual FlightStreams read(const FlightLogOptions& options) const = 0;
};

}  // namespace propulsion_estimator
