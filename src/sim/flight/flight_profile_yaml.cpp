#include "propulsion_estimator/sim/flight/flight_profile_yaml.h"

#include <filesystem>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {
namespace sim {
namespace {

Eigen::Vector3d readVector(const YamlMap& map, const std::string& key) {
  const std::vector<double> values = map.numbers(key);
  if (values.size() != 3) map.fail(key, "expected [x, y, z], got " + std::to_string(values.size()) + " numbers");
  return Eigen::Vector3d(values[0], values[1], values[2]);
}

AutopilotParams readAutopilot(const YamlMap& map) {
  map.allowOnly({"flavour", "pwm_min_us", "pwm_max_us", "disarmed_pwm_us", "rc_out_rate_hz"});
  AutopilotParams autopilot;
  autopilot.flavour =
      map.choice("flavour", {"px4", "ardupilot"}) == "px4" ? AutopilotFlavour::kPx4 : AutopilotFlavour::kArduPilot;
  autopilot.pwm_min_us = map.number("pwm_min_us");
  autopilot.pwm_max_us = map.number("pwm_max_us");
  autopilot.disarmed_pwm_us = map.number("disarmed_pwm_us");
  autopilot.rc_out_rate_hz = map.number("rc_out_rate_hz");
  return autopilot;
}

// Every key is required: a vehicle's parts are its calibration, not a default.
VehicleParts readParts(const YamlMap& map) {
  map.allowOnly({"seed", "thrust_coefficient_spread", "torque_coefficient_spread", "kv_spread",
                 "esc_end_point_spread_us", "spin_torque_ratio"});
  const int seed = map.integer("seed");
  if (seed < 0) map.fail("seed", std::to_string(seed) + " is outside 0..1000000000");
  VehicleParts parts;
  parts.seed = static_cast<std::uint64_t>(seed);
  parts.thrust_coefficient_spread = map.number("thrust_coefficient_spread");
  parts.torque_coefficient_spread = map.number("torque_coefficient_spread");
  parts.kv_spread = map.number("kv_spread");
  parts.esc_end_point_spread_us = map.number("esc_end_point_spread_us");
  parts.spin_torque_ratio = map.number("spin_torque_ratio");
  return parts;
}

VehicleSetup readVehicle(const YamlMap& map, const std::string& folder) {
  map.allowOnly({"urdf", "centre_of_mass_offset_m", "landing_gear", "drag_area_m2", "battery_initial_soc",
                 "avionics_current_a", "parts"});
  VehicleSetup vehicle;
  const std::string urdf = map.text("urdf");
  vehicle.urdf_path =
      std::filesystem::path(urdf).is_absolute() ? urdf : (std::filesystem::path(folder) / urdf).string();
  vehicle.centre_of_mass_offset_m = readVector(map, "centre_of_mass_offset_m");
  const YamlMap gear = map.map("landing_gear");
  gear.allowOnly({"height_m", "half_width_m"});
  vehicle.landing_gear_height_m = gear.number("height_m");
  vehicle.landing_gear_half_width_m = gear.number("half_width_m");
  vehicle.drag_area_m2 = map.number("drag_area_m2");
  vehicle.battery_initial_soc = map.number("battery_initial_soc");
  if (map.has("avionics_current_a")) vehicle.avionics_current_a = map.number("avionics_current_a");
  if (map.has("parts")) vehicle.parts = readParts(map.map("parts"));
  return vehicle;
}

PayloadCable readCable(const YamlMap& map) {
  map.allowOnly({"length_m", "attach_point_m", "stiffness_n_per_m", "damping_n_s_per_m"});
  return PayloadCable{map.number("length_m"), readVector(map, "attach_point_m"), map.number("stiffness_n_per_m"),
                      map.number("damping_n_s_per_m")};
}

VehicleFaults readFaults(const YamlMap& map) {
  map.allowOnly({"weak_propeller"});
  VehicleFaults faults;
  if (map.has("weak_propeller")) {
    const YamlMap weak = map.map("weak_propeller");
    weak.allowOnly({"motor", "thrust_factor", "damage"});
    faults.weak_propeller =
        PropellerFault{weak.integer("motor"), weak.number("thrust_factor"),
                       weak.choice("damage", {"chipped", "worn"}) == "worn" ? PropellerDamage::kWorn
                                                                            : PropellerDamage::kChipped};
  }
  return faults;
}

FlightSegment readSegment(const YamlMap& map) {
  FlightSegment segment;
  const std::string type =
      map.choice("type", {"wait", "takeoff", "hover", "climb", "descend", "land", "payload", "move"});
  if (type == "wait" || type == "hover") {
    map.allowOnly({"type", "duration_s"});
    segment.kind = type == "wait" ? SegmentKind::kWait : SegmentKind::kHover;
    segment.duration_s = map.number("duration_s");
  } else if (type == "payload") {
    map.allowOnly({"type", "mass_kg", "duration_s"});
    segment.kind = SegmentKind::kPayload;
    segment.payload_mass_kg = map.number("mass_kg");
    segment.duration_s = map.number("duration_s");
  } else if (type == "move") {
    map.allowOnly({"type", "east_m", "north_m", "speed_m_s"});
    segment.kind = SegmentKind::kMove;
    segment.displacement_m = Eigen::Vector2d(map.number("east_m"), map.number("north_m"));
    segment.speed_m_s = map.number("speed_m_s");
  } else if (type == "land") {
    map.allowOnly({"type", "rate_m_s"});
    segment.kind = SegmentKind::kLand;
    segment.rate_m_s = map.number("rate_m_s");
  } else {
    map.allowOnly({"type", "height_m", "rate_m_s"});
    segment.kind = type == "takeoff" ? SegmentKind::kTakeoff
                   : type == "climb" ? SegmentKind::kClimb
                                     : SegmentKind::kDescend;
    segment.height_m = map.number("height_m");
    segment.rate_m_s = map.number("rate_m_s");
  }
  return segment;
}

}  // namespace

FlightProfile parseFlightProfileYaml(const std::string& text, const std::string& source) {
  const YamlMap root = parseYamlDocument(text, source);
  root.allowOnly({"autopilot", "vehicle", "payload_cable", "faults", "manifest", "segments"});
  FlightProfile profile;
  profile.source = source;
  profile.autopilot = readAutopilot(root.map("autopilot"));
  profile.vehicle = readVehicle(root.map("vehicle"), std::filesystem::path(source).parent_path().string());
  profile.cable = readCable(root.map("payload_cable"));
  if (root.has("faults")) profile.faults = readFaults(root.map("faults"));
  const YamlMap manifest = root.map("manifest");
  manifest.allowOnly({"settle_s", "spans"});
  profile.manifest_settle_s = manifest.number("settle_s");
  if (manifest.has("spans") && manifest.choice("spans", {"hovers", "airborne"}) == "airborne") {
    profile.manifest_spans = ManifestSpans::kAirborne;
  }
  for (const YamlMap& segment : root.maps("segments")) profile.segments.push_back(readSegment(segment));
  validateAt(root, profile);
  return profile;
}

FlightProfile loadFlightProfileFile(const std::string& path) {
  return parseFlightProfileYaml(readTextFile(path), path);
}

}  // namespace sim
}  // namespace propulsion_estimator
