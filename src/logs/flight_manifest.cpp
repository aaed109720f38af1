#include "propulsion_estimator/logs/flight_manifest.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {

void ManifestFlight::validate(const std::string& at) const {
  if (log.empty()) throw FieldError(at + ".log", "is empty");
  if (segments.empty()) throw FieldError(at + ".segments", "no segments");
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const ManifestSegment& segment = segments[s];
    const std::string field = at + ".segments[" + std::to_string(s) + "].";
    if (!(segment.start_s >= 0.0)) throw FieldError(field + "start", formatNumber(segment.start_s) + " is negative");
    if (!(segment.end_s > segment.start_s)) {
      throw FieldError(field + "end",
                       formatNumber(segment.end_s) + " is not after start " + formatNumber(segment.start_s));
    }
    requirePositive(field + "mass_kg", segment.mass_kg, 100.0, " kg");
    if (s > 0 && segment.start_s < segments[s - 1].end_s) {
      throw FieldError(field + "start", formatNumber(segment.start_s) + " is before the previous segment's end " +
                                            formatNumber(segments[s - 1].end_s));
    }
  }
}

void FlightManifest::validate() const {
  if (flights.empty()) throw FieldError("flights", "no flights");
  for (std::size_t f = 0; f < flights.size(); ++f) flights[f].validate("flights[" + std::to_string(f) + "]");
}

namespace {

// The file's structure and keys, not yet its values.
std::vector<ManifestFlight> readFlights(const YamlMap& root) {
  root.allowOnly({"flights"});
  std::vector<ManifestFlight> flights;
  for (const YamlMap& flight : root.maps("flights")) {
    flight.allowOnly({"log", "bag", "segments"});
    ManifestFlight entry;
    // `bag:`, the field's name before logs of other formats were read, is still read.
    if (flight.has("log") && flight.has("bag")) flight.fail("bag", "give log or bag (its old name), not both");
    entry.log = flight.text(flight.has("bag") ? "bag" : "log");
    for (const YamlMap& segment : flight.maps("segments")) {
      segment.allowOnly({"start", "end", "mass_kg"});
      entry.segments.push_back({segment.number("start"), segment.number("end"), segment.number("mass_kg")});
    }
    flights.push_back(entry);
  }
  return flights;
}

}  // namespace

FlightManifest parseFlightManifest(const std::string& text, const std::string& source) {
  const YamlMap root = parseYamlDocument(text, source);
  FlightManifest manifest{readFlights(root)};
  validateAt(root, manifest);
  return manifest;
}

FlightManifest loadFlightManifest(const std::string& path) { return parseFlightManifest(readTextFile(path), path); }

std::vector<ManifestEntry> loadFlightManifestEntries(const std::string& path) {
  const YamlMap root = parseYamlDocument(readTextFile(path), path);
  std::vector<ManifestEntry> entries;
  for (ManifestFlight& flight : readFlights(root)) entries.push_back({std::move(flight), ""});
  if (entries.empty()) throwAtField(root, FieldError("flights", "no flights"));
  for (std::size_t f = 0; f < entries.size(); ++f) {
    try {
      entries[f].flight.validate("flights[" + std::to_string(f) + "]");
    } catch (const FieldError& error) {
      try {
        throwAtField(root, error);
      } catch (const ConfigError& located) {
        entries[f].refusal = located.what();
      }
    }
  }
  return entries;
}

std::string flightManifestToYaml(const FlightManifest& manifest, const std::string& comment) {
  manifest.validate();
  YAML::Emitter out;
  if (!comment.empty()) out << YAML::Comment(comment) << YAML::Newline;
  out << YAML::BeginMap << YAML::Key << "flights" << YAML::Value << YAML::BeginSeq;
  for (const ManifestFlight& flight : manifest.flights) {
    out << YAML::BeginMap << YAML::Key << "log" << YAML::Value << flight.log;
    out << YAML::Key << "segments" << YAML::Value << YAML::BeginSeq;
    for (const ManifestSegment& segment : flight.segments) {
      out << YAML::Flow << YAML::BeginMap;
      out << YAML::Key << "start" << YAML::Value << formatNumber(segment.start_s);
      out << YAML::Key << "end" << YAML::Value << formatNumber(segment.end_s);
      out << YAML::Key << "mass_kg" << YAML::Value << formatNumber(segment.mass_kg);
      out << YAML::EndMap;
    }
    out << YAML::EndSeq << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void saveFlightManifest(const FlightManifest& manifest, const std::string& path, const std::string& comment) {
  writeTextFile(path, flightManifestToYaml(manifest, comment));
}

std::string resolveLogPath(const std::string& manifest_path, const std::string& log) {
  const std::filesystem::path path(log);
  if (path.is_absolute()) return log;
  return (std::filesystem::path(manifest_path).parent_path() / path).string();
}

}  // namespace propulsion_estimator
