#pragma once

#include <string>
#include <vector>

namespace propulsion_estimator {

/// A stretch of a flight whose lifted mass is known (weighed): the ground truth of the estimator's
/// tests and the input of the gap diagnosis.
struct ManifestSegment {
  double start_s = 0.0;  ///< seconds from the log's first message
  double end_s = 0.0;    ///< seconds from the log's first message
  double mass_kg = 0.0;  ///< vehicle plus hanging payload
};

/// One flight of a manifest: its log (a rosbag or any format flight_log_formats.h knows) and
/// either the segments whose mass is known, or the mass of its airborne stretches (take-off to
/// landing, found in the log by the tool that reads it).
struct ManifestFlight {
  std::string log;  ///< as written in the manifest (`log:`, or `bag:`): relative to its folder, or absolute
  std::vector<ManifestSegment> segments;  ///< in time order, not overlapping
  /// Instead of segments (`mass_kg:` of the flight), kg: one value for every airborne stretch of
  /// the log, or one per stretch in time order.
  std::vector<double> airborne_mass_kg;

  /// Throws FieldError named from `at` ("flights[1]" gives "flights[1].segments[2].end") for a
  /// flight without log, with neither or both of segments and mass_kg, a segment with start < 0,
  /// end <= start, a mass outside 0..100 kg, or segments out of order or overlapping.
  void validate(const std::string& at) const;
};

/// A set of flights (`bag:` is read as `log:`, its name before other formats were read):
///   flights:
///     - log: flight_01.bag
///       segments:
///         - {start: 5.0, end: 178.0, mass_kg: 1.315}
///     - log: flight_02.ulg
///       mass_kg: 1.315            # the whole airborne stretch; [1.315, 1.52]: each stretch's
struct FlightManifest {
  std::vector<ManifestFlight> flights;  ///< at least one

  /// Throws FieldError for no flights, or the first flight ManifestFlight::validate refuses.
  void validate() const;
};

/// The manifest's reader and writer: parseFlightManifest(flightManifestToYaml(m)) == m.
/// Refusals are ConfigError "<file>:<line>: <key>: <problem>".
FlightManifest parseFlightManifest(const std::string& text, const std::string& source);
/// Reads and parses the manifest file `path`; InputError when it cannot be read.
FlightManifest loadFlightManifest(const std::string& path);
/// The manifest as YAML, `comment` on top; parseFlightManifest reads it back to the same manifest.
std::string flightManifestToYaml(const FlightManifest& manifest, const std::string& comment = "");
/// Writes flightManifestToYaml's text to `path`; InputError when it cannot be written.
void saveFlightManifest(const FlightManifest& manifest, const std::string& path, const std::string& comment = "");

/// A manifest for a tool that goes on with the flights it can use: read as loadFlightManifest
/// reads it (a refusal of the file as a whole, no flights included, throws ConfigError), except
/// that a flight ManifestFlight::validate refuses is kept with its refusal, located as
/// loadFlightManifest would locate it ("<file>:<line>: flights[1].segments[0].mass_kg: 0 is
/// outside 0..100 kg").
struct ManifestEntry {
  ManifestFlight flight;  ///< the flight as read
  std::string refusal;  ///< empty for a usable flight
};
/// Reads the manifest file `path` flight by flight (see ManifestEntry); a `log:` with a pattern
/// (`logs/*.ulg`) is one flight per matching file, in name order, each with the same segments or
/// masses (its log then the file's absolute path), and a refusal when nothing matches
/// ("<file>:<line>: flights[2].log: logs/*.ulg matches no file"). InputError when the file cannot
/// be read, ConfigError for a refusal of the file as a whole.
std::vector<ManifestEntry> loadFlightManifestEntries(const std::string& path);

/// A flight's log path as a file path: relative paths are taken from the manifest's folder.
std::string resolveLogPath(const std::string& manifest_path, const std::string& log);

}  // namespace propulsion_estimator
