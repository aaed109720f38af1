#include "propulsion_estimator/onboard/pack_file.h"

#include <cmath>
#include <filesystem>
#include <system_error>

#include <yaml-cpp/yaml.h>

#include "propulsion_estimator/common/atomic_file.h"
#include "propulsion_estimator/common/cells_in_series.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {
namespace {

void emitList(YAML::Emitter* yaml, const char* key, const std::vector<double>& values) {
  *yaml << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (double value : values) *yaml << formatNumber(value);
  *yaml << YAML::EndSeq;
}

// "pack "A"" in the lines of the log and the diagnostics.
std::string named(const std::string& pack_id) { return "pack \"" + pack_id + "\""; }

}  // namespace

PackRecord parsePackFile(const std::string& text, const std::string& source) {
  const YamlMap root = parseYamlDocument(text, source);
  root.allowOnly({"pack_id", "cells", "flights", "capacity_ah", "ocv_soc", "ocv_cell_v", "resistance_ohm",
                  "rest_offset_cell_v"});
  PackRecord record;
  record.pack_id = root.text("pack_id");
  if (record.pack_id.empty()) root.fail("pack_id", "must not be empty");
  record.cells = root.integer("cells");
  if (const std::string problem = cellsInSeriesProblem(record.cells); !problem.empty()) root.fail("cells", problem);
  record.flights = root.integer("flights");
  if (record.flights < 0) root.fail("flights", "must not be negative");
  record.capacity_ah = root.optionalNumber("capacity_ah");
  if (record.capacity_ah && !(*record.capacity_ah > 0.0)) root.fail("capacity_ah", "must be positive");
  record.ocv_soc = root.numbers("ocv_soc");
  record.ocv_cell_v = root.numbers("ocv_cell_v");
  if (record.ocv_soc.size() != record.ocv_cell_v.size()) {
    root.fail("ocv_cell_v", "has " + std::to_string(record.ocv_cell_v.size()) + " points, ocv_soc " +
                                std::to_string(record.ocv_soc.size()));
  }
  for (std::size_t k = 0; k < record.ocv_soc.size(); ++k) {
    if (record.ocv_soc[k] < 0.0 || record.ocv_soc[k] > 1.0) root.fail("ocv_soc", "must lie within 0..1");
    if (k > 0 && !(record.ocv_soc[k] > record.ocv_soc[k - 1])) root.fail("ocv_soc", "must increase");
    if (record.ocv_cell_v[k] < 2.0 || record.ocv_cell_v[k] > 4.5) root.fail("ocv_cell_v", "must lie within 2..4.5 V");
    if (k > 0 && !(record.ocv_cell_v[k] > record.ocv_cell_v[k - 1])) root.fail("ocv_cell_v", "must increase");
  }
  record.resistance_ohm = root.numbers("resistance_ohm");
  record.rest_offset_cell_v = root.optionalNumber("rest_offset_cell_v");
  if (record.rest_offset_cell_v && std::abs(*record.rest_offset_cell_v) > 0.5) {
    root.fail("rest_offset_cell_v", "must lie within -0.5..0.5 V");
  }
  for (double r : record.resistance_ohm) {
    if (r < 0.0) root.fail("resistance_ohm", "must not be negative");
  }
  return record;
}

std::string packFileText(const PackRecord& r) {
  YAML::Emitter yaml;
  yaml << YAML::Comment("Written by propulsion_estimator: what it learned of one battery pack from its flights.")
       << YAML::Newline << YAML::BeginMap;
  yaml << YAML::Key << "pack_id" << YAML::Value << YAML::DoubleQuoted << r.pack_id;
  yaml << YAML::Key << "cells" << YAML::Value << r.cells << YAML::Key << "flights" << YAML::Value << r.flights;
  if (r.capacity_ah) yaml << YAML::Key << "capacity_ah" << YAML::Value << formatNumber(*r.capacity_ah);
  emitList(&yaml, "ocv_soc", r.ocv_soc);
  emitList(&yaml, "ocv_cell_v", r.ocv_cell_v);
  emitList(&yaml, "resistance_ohm", r.resistance_ohm);
  if (r.rest_offset_cell_v) yaml << YAML::Key << "rest_offset_cell_v" << YAML::Value << formatNumber(*r.rest_offset_cell_v);
  yaml << YAML::EndMap;
  return std::string(yaml.c_str()) + "\n";
}

std::optional<PackRecord> loadPackFile(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return std::nullopt;
  return parsePackFile(readTextFile(path), path);
}

void savePackFile(const std::string& path, const PackRecord& record) {
  writeFileAtomically(path, packFileText(record), "pack file");
}

std::string packFilePath(const std::string& pattern, const std::string& pack_id) {
  static const std::string kPlaceholder = "{pack_id}";
  std::string path = pattern;
  for (std::size_t at = path.find(kPlaceholder); at != std::string::npos; at = path.find(kPlaceholder, at + pack_id.size())) {
    path.replace(at, kPlaceholder.size(), pack_id);
  }
  return path;
}

PackFileLookup packFileRecordFor(const std::string& path, const std::string& pack_id, int cells) {
  PackFileLookup lookup;
  std::optional<PackRecord> record = loadPackFile(path);
  if (!record) {
    lookup.note = path + ": none yet for " + named(pack_id) + ": learned from this flight";
  } else if (record->pack_id != pack_id) {
    lookup.writable = false;
    lookup.note = path + ": holds " + named(record->pack_id) + ", not this flight's \"" + pack_id + "\"" +
                  ": not used, not overwritten (put {pack_id} in capability/battery/pack_file for a file per pack)";
  } else if (record->cells != cells) {
    lookup.writable = false;
    lookup.note = path + ": " + named(pack_id) + " has " + std::to_string(record->cells) + " cells there, " +
                  std::to_string(cells) + " configured: not used, not overwritten";
  } else {
    lookup.note = path + ": " + named(pack_id) + ", " + std::to_string(record->flights) + " flights learned";
    lookup.record = std::move(record);
  }
  return lookup;
}

}  // namespace propulsion_estimator
