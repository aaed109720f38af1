#pragma once

#include <limits>
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
  /// The PWM range in us that normalised motor outputs (PX4's actuator_motors, 0..1) map onto;
  /// required only by a log whose outputs are logged normalised alone. NaN: not given.
  double pwm_min_us = std::numeric_limits<double>::quiet_NaN();  ///< normalised 0 maps here, us
  double pwm_max_us = std::numeric_limits<double>::quiet_NaN();  ///< normalised 1 maps here, us

  /// Throws ConfigError "<what>: ..." for motors outside 1..kMaxMotors, a source whose name is
  /// not a signal, or a PWM range given by half or not within 500..2500 us with min < max; `what`
  /// names the input the options came from ("--topic", a file).
  void validate(const std::string& what) const;

  /// For a format that finds its signals by its own names (`format`: "a ULog"): "" without
  /// sources, else the line saying the sources given were not used. Throws nothing.
  std::string unusedSourcesNote(const std::string& format) const;
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
  /// "" for a log read to its end; else the one line that refused the rest of it ("<path>: at
  /// byte <offset>: <message>: <problem>"; a rosbag's "<path>: reading failed after <t> s: <why>",
  /// known once read() has run): read() then gives what came before.
  virtual std::string refusal() const { return ""; }
  /// Whether the log's signals are found where FlightLogOptions::sources names them (a rosbag's
  /// topics); false: by the format's own names, which read() lists in FlightStreams::notes.
  virtual bool readsNamedSources() const { return false; }
};

/// The whole of the flight log `path`, for a reader that parses it in memory. InputError
/// as requireRegularFile (no such file, a folder, a device), or naming it when it cannot be read.
std::string readFlightLogBytes(const std::string& path);

/// `bytes` as C would spell them: printable ASCII as is, other bytes (a newline, a NUL) as `\xNN`;
/// for text taken from a log into a one-line message.
std::string printableBytes(const std::string& bytes);

/// A reader's `line` without its leading "<path>: ", for a message that names the log already;
/// `line` itself when it does not start so.
std::string withoutLogPath(const std::string& line, const std::string& path);
/// "<path>: <nothing>", and the file's `refusal` in brackets, named once, when it has one: the line
/// of a log whose reading stopped before anything usable ("f.ulg: no data messages (at byte 69: ...)").
std::string nothingReadLine(const std::string& path, const std::string& nothing, const std::string& refusal);

}  // namespace propulsion_estimator
