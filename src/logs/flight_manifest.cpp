#include "propulsion_estimator/logs/flight_manifest.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/yaml_map.h"
#include "propulsion_estimator/logs/file_pattern.h"

namespace propulsion_estimator {

void ManifestFlight::validate(const std::string& at) const {
  if (log.empty()) throw FieldError(at + ".log", "is empty");
  if (!segments.empty() && !airborne_mass_kg.empty()) {
    throw FieldError(at + ".mass_kg", "give segments or the flight's mass_kg, not both");
  }
  if (segments.empty() && airborne_mass_kg.empty()) {
    throw FieldError(at + ".segments", "no segments (or mass_kg for the whole airborne stretch)");
  }
  for (std::size_t m = 0; m < airborne_mass_kg.size(); ++m) {
    const std::string field = at + ".mass_kg" + (airborne_mass_kg.size() > 1 ? "[" + std::to_string(m) + "]" : "");
    requirePositive(field, airborne_mass_kg[m], 100.0, " kg");
  }
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
    flight.allowOnly({"log", "bag", "segments", "mass_kg"});
    ManifestFlight entry;
    // `bag:`, the field's name before logs of other formats were read, is still read.
    if (flight.has("log") && flight.has("bag")) flight.fail("bag", "give log or bag (its old name), not both");
    entry.log = flight.text(flight.has("bag") ? "bag" : "log");
    if (flight.has("mass_kg")) {
      entry.airborne_mass_kg =
          flight.isSequence("mass_kg") ? flight.numbers("mass_kg") : std::vector<double>{flight.number("mass_kg")};
    }
    if (!flight.has("segments")) {
      flights.push_back(entry);
      continue;
    }
    for (const YamlMap& segment : flight.maps("segments")) {
      segment.allowOnly({"start", "end", "mass_kg"});
      entry.segments.push_back({segment.number("start"), segment.number("end"), segment.number("mass_kg")});
    }
    flights.push_back(entry);
  }
  return flights;
}

// `error` with the line of its field, as loadFlightManifest would throw it.
std::string located(const YamlMap& root, const FieldError& error) {
  try {
    throwAtField(root, error);
  } catch (const ConfigError& refusal) {
    return refusal.what();
  }
}

// A flight ManifestFlight::validate refuses, located; "" when it is usable.
std::string locatedRefusal(const YamlMap& root, const ManifestFlight& flight, const std::string& at) {
  try {
    flight.validate(at);
  } catch (const FieldError& error) {
    return located(root, error);
  }
  return "";
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
  const std::vector<ManifestFlight> flights = readFlights(root);
  if (flights.empty()) throwAtField(root, FieldError("flights", "no flights"));
  std::vector<ManifestEntry> entries;
  for (std::size_t f = 0; f < flights.size(); ++f) {
    const std::string at = "flights[" + std::to_string(f) + "]";
    ManifestEntry entry{flights[f], locatedRefusal(root, flights[f], at)};
    if (!entry.refusal.empty() || !isFilePattern(flights[f].log)) {
      entries.push_back(std::move(entry));
      continue;
    }
    const std::vector<std::string> matches = matchingFiles(resolveLogPath(path, flights[f].log));
    if (matches.empty()) {
      entries.push_back({flights[f], located(root, FieldError(at + ".log", flights[f].log + " matches no file"))});
    }
    for (const std::string& match : matches) {
      entries.push_back({flights[f], ""});
      // Absolute: a match spelt from the manifest's folder would be resolved from it again.
      entries.back().flight.log = std::filesystem::absolute(match).lexically_normal().string();
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
    if (!flight.airborne_mass_kg.empty()) {
      out << YAML::Key << "mass_kg" << YAML::Value;
      if (flight.airborne_mass_kg.size() == 1) {
        out << formatNumber(flight.airborne_mass_kg[0]);
      } else {
        out << YAML::Flow << YAML::BeginSeq;
        for (double mass : flight.airborne_mass_kg) out << formatNumber(mass);
        out << YAML::EndSeq;
      }
      out << YAML::EndMap;
      continue;
    }
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
