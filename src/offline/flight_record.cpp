#include "propulsion_estimator/offline/flight_record.h"

#include <cmath>

#include <yaml-cpp/yaml.h>

#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/yaml_map.h"
#include "propulsion_estimator/onboard/model_check.h"

namespace propulsion_estimator {
namespace offline {
namespace {

constexpr const char* kFormat = "propulsion_estimator/flight_record";
constexpr int kVersion = 1;

// A NaN figure is left out: the reader takes an absent key as NaN.
void emitNumber(YAML::Emitter* yaml, const char* key, double value) {
  if (!std::isnan(value)) *yaml << YAML::Key << key << YAML::Value << formatNumber(value);
}

double optional(const YamlMap& map, const char* key) { return map.optionalNumber(key).value_or(kNaN); }

void emitTexts(YAML::Emitter* yaml, const char* key, const std::vector<std::string>& texts) {
  *yaml << YAML::Key << key << YAML::Value << YAML::BeginSeq;
  for (const std::string& text : texts) *yaml << YAML::DoubleQuoted << text;
  *yaml << YAML::EndSeq;
}

void emitHover(YAML::Emitter* yaml, const HoverEpisode& h) {
  *yaml << YAML::Flow << YAML::BeginMap;
  emitNumber(yaml, "start_s", h.start_s);
  emitNumber(yaml, "end_s", h.end_s);
  emitNumber(yaml, "total_mass_kg", h.total_mass_kg);
  emitNumber(yaml, "mass_std_kg", h.mass_std_kg);
  emitNumber(yaml, "payload_kg", h.payload_kg);
  emitNumber(yaml, "window_s", h.window_s);
  emitNumber(yaml, "voltage_v", h.voltage_v);
  emitNumber(yaml, "thrust_to_weight", h.thrust_to_weight);
  emitNumber(yaml, "max_additional_payload_kg", h.max_additional_payload_kg);
  *yaml << YAML::EndMap;
}

HoverEpisode readHover(const YamlMap& map) {
  map.allowOnly({"start_s", "end_s", "total_mass_kg", "mass_std_kg", "payload_kg", "window_s", "voltage_v",
                 "thrust_to_weight", "max_additional_payload_kg"});
  HoverEpisode h;
  h.start_s = map.number("start_s");
  h.end_s = map.number("end_s");
  h.total_mass_kg = optional(map, "total_mass_kg");
  h.mass_std_kg = optional(map, "mass_std_kg");
  h.payload_kg = optional(map, "payload_kg");
  h.window_s = optional(map, "window_s");
  h.voltage_v = optional(map, "voltage_v");
  h.thrust_to_weight = optional(map, "thrust_to_weight");
  h.max_additional_payload_kg = optional(map, "max_additional_payload_kg");
  return h;
}

void emitMotorHealth(YAML::Emitter* yaml, const MotorHealthVerdict& v) {
  *yaml << YAML::BeginMap << YAML::Key << "judged" << YAML::Value << v.judged;
  if (!v.judged) *yaml << YAML::Key << "unavailable" << YAML::Value << YAML::DoubleQuoted << v.unavailable;
  *yaml << YAML::Key << "blocks" << YAML::Value << v.blocks;
  *yaml << YAML::Key << "flagged_channel" << YAML::Value << v.flagged_channel;
  emitNumber(yaml, "yaw_imbalance", v.yaw_imbalance);
  emitNumber(yaml, "yaw_imbalance_std", v.yaw_imbalance_std);
  emitNumber(yaml, "cg_offset_x_m", v.cg_offset_x_m);
  emitNumber(yaml, "cg_offset_y_m", v.cg_offset_y_m);
  *yaml << YAML::Key << "motors" << YAML::Value << YAML::BeginSeq;
  for (const MotorBalanceGap& m : v.motors) {
    *yaml << YAML::Flow << YAML::BeginMap << YAML::Key << "channel" << YAML::Value << m.channel;
    emitNumber(yaml, "thrust_gap", m.thrust_gap);
    emitNumber(yaml, "thrust_gap_std", m.thrust_gap_std);
    *yaml << YAML::EndMap;
  }
  *yaml << YAML::EndSeq << YAML::EndMap;
}

int readChannel(const YamlMap& map, const char* key, int lowest) {
  const int channel = map.integer(key);
  if (channel < lowest) map.fail(key, std::to_string(channel) + " is not a channel (they count from 1)");
  return channel;
}

MotorHealthVerdict readMotorHealth(const YamlMap& map) {
  map.allowOnly({"judged", "unavailable", "blocks", "flagged_channel", "yaw_imbalance", "yaw_imbalance_std",
                 "cg_offset_x_m", "cg_offset_y_m", "motors"});
  MotorHealthVerdict v;
  v.judged = map.boolean("judged");
  v.unavailable = map.optionalText("unavailable").value_or("");
  v.blocks = map.integer("blocks");
  v.flagged_channel = readChannel(map, "flagged_channel", 0);
  v.yaw_imbalance = optional(map, "yaw_imbalance");
  v.yaw_imbalance_std = optional(map, "yaw_imbalance_std");
  v.cg_offset_x_m = optional(map, "cg_offset_x_m");
  v.cg_offset_y_m = optional(map, "cg_offset_y_m");
  for (const YamlMap& motor : map.maps("motors")) {
    motor.allowOnly({"channel", "thrust_gap", "thrust_gap_std"});
    v.motors.push_back({readChannel(motor, "channel", 1), optional(motor, "thrust_gap"), optional(motor, "thrust_gap_std")});
  }
  return v;
}

}  // namespace

FlightRecord flightRecordOf(const FlightEstimate& e) {
  FlightRecord r;
  r.source = e.source;
  r.duration_s = e.duration_s;
  r.empty_mass_kg = e.empty_mass_kg;
  r.hovers = e.hovers;
  r.motor_health = e.motor_health;
  r.flagged_channels = e.flagged_channels;
  r.pack_resistance_ohm = e.pack_resistance_ohm;
  r.pack_resistance_std_ohm = e.pack_resistance_std_ohm;
  r.esc_verdict = modelCheckVerdictName(e.esc_check.verdict);
  r.esc_flagged_channel = e.esc_check.flagged_channel;
  r.supply_resistance_ohm = e.esc_check.supply_resistance_ohm;
  r.esc_flags = e.esc_flags;
  r.log_damage = e.log_damage;
  r.warnings = e.warnings;
  return r;
}

std::string flightRecordText(const FlightRecord& r) {
  YAML::Emitter yaml;
  yaml << YAML::Comment("Written by propulsion_estimator's estimate: what it said of one flight (SI units).")
       << YAML::Newline << YAML::BeginMap;
  yaml << YAML::Key << "format" << YAML::Value << kFormat << YAML::Key << "version" << YAML::Value << kVersion;
  yaml << YAML::Key << "source" << YAML::Value << YAML::DoubleQuoted << r.source;
  yaml << YAML::Key << "duration_s" << YAML::Value << formatNumber(r.duration_s);
  emitNumber(&yaml, "empty_mass_kg", r.empty_mass_kg);
  yaml << YAML::Key << "hovers" << YAML::Value << YAML::BeginSeq;
  for (const HoverEpisode& h : r.hovers) emitHover(&yaml, h);
  yaml << YAML::EndSeq;
  yaml << YAML::Key << "motor_health" << YAML::Value;
  emitMotorHealth(&yaml, r.motor_health);
  yaml << YAML::Key << "flagged_channels" << YAML::Value << YAML::Flow << r.flagged_channels;
  yaml << YAML::Key << "pack" << YAML::Value << YAML::BeginMap;
  emitNumber(&yaml, "internal_resistance_ohm", r.pack_resistance_ohm);
  emitNumber(&yaml, "internal_resistance_std_ohm", r.pack_resistance_std_ohm);
  yaml << YAML::EndMap;
  yaml << YAML::Key << "esc" << YAML::Value << YAML::BeginMap;
  yaml << YAML::Key << "verdict" << YAML::Value << r.esc_verdict;
  yaml << YAML::Key << "flagged_channel" << YAML::Value << r.esc_flagged_channel;
  emitNumber(&yaml, "supply_resistance_ohm", r.supply_resistance_ohm);
  emitTexts(&yaml, "flags", r.esc_flags);
  yaml << YAML::EndMap;
  yaml << YAML::Key << "log_damage" << YAML::Value << YAML::DoubleQuoted << r.log_damage;
  emitTexts(&yaml, "warnings", r.warnings);
  yaml << YAML::EndMap;
  return std::string(yaml.c_str()) + "\n";
}

FlightRecord parseFlightRecord(const std::string& text, const std::string& source) {
  const YamlMap root = parseYamlDocument(text, source);
  root.allowOnly({"format", "version", "source", "duration_s", "empty_mass_kg", "hovers", "motor_health", "flagged_channels",
                  "pack", "esc", "log_damage", "warnings"});
  if (root.text("format") != kFormat) root.fail("format", "'" + root.text("format") + "' is not " + kFormat);
  if (root.integer("version") != kVersion) {
    root.fail("version", std::to_string(root.integer("version")) + " is not " + std::to_string(kVersion) +
                             ", the version this build reads");
  }
  FlightRecord r;
  r.source = root.text("source");
  r.duration_s = root.number("duration_s");
  if (r.duration_s < 0.0) root.fail("duration_s", formatNumber(r.duration_s) + " is negative");
  r.empty_mass_kg = optional(root, "empty_mass_kg");
  for (const YamlMap& hover : root.maps("hovers")) r.hovers.push_back(readHover(hover));
  r.motor_health = readMotorHealth(root.map("motor_health"));
  for (double channel : root.numbers("flagged_channels")) {
    if (channel < 1 || channel != std::floor(channel)) {
      root.fail("flagged_channels", formatNumber(channel) + " is not a channel (they count from 1)");
    }
    r.flagged_channels.push_back(static_cast<int>(channel));
  }
  const YamlMap pack = root.map("pack");
  pack.allowOnly({"internal_resistance_ohm", "internal_resistance_std_ohm"});
  r.pack_resistance_ohm = optional(pack, "internal_resistance_ohm");
  r.pack_resistance_std_ohm = optional(pack, "internal_resistance_std_ohm");
  const YamlMap esc = root.map("esc");
  esc.allowOnly({"verdict", "flagged_channel", "supply_resistance_ohm", "flags"});
  r.esc_verdict = esc.choice("verdict", {"not_judged", "consistent", "propeller", "motor_esc", "supply"});
  r.esc_flagged_channel = readChannel(esc, "flagged_channel", 0);
  r.supply_resistance_ohm = optional(esc, "supply_resistance_ohm");
  r.esc_flags = esc.texts("flags");
  r.log_damage = root.text("log_damage");
  r.warnings = root.texts("warnings");
  return r;
}

}  // namespace offline
}  // namespace propulsion_estimator
