#include "propulsion_estimator/sim/physics/sim_params_yaml.h"

#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/sim/physics/atmosphere_yaml.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {
namespace sim {
namespace {

constexpr int kFormatVersion = 1;

EscParams readEsc(const YamlMap& map) {
  map.allowOnly({"name", "pwm_zero_us", "pwm_full_us", "resistance_ohm"});
  return EscParams{map.text("name"), map.number("pwm_zero_us"), map.number("pwm_full_us"),
                   map.number("resistance_ohm")};
}

BldcMotorParams readMotor(const YamlMap& map) {
  map.allowOnly({"name", "kv_rpm_per_v", "winding_resistance_ohm", "no_load_current_a", "reference_temperature_c",
                 "flux_temperature_coefficient_per_c", "rotor_inertia_kg_m2", "thermal_capacity_j_per_c",
                 "thermal_resistance_c_per_w"});
  BldcMotorParams motor;
  motor.name = map.text("name");
  motor.kv_rpm_per_v = map.number("kv_rpm_per_v");
  motor.winding_resistance_ohm = map.number("winding_resistance_ohm");
  motor.no_load_current_a = map.number("no_load_current_a");
  motor.reference_temperature_c = map.number("reference_temperature_c");
  motor.flux_temperature_coefficient_per_c = map.number("flux_temperature_coefficient_per_c");
  motor.rotor_inertia_kg_m2 = map.number("rotor_inertia_kg_m2");
  motor.thermal_capacity_j_per_c = map.number("thermal_capacity_j_per_c");
  motor.thermal_resistance_c_per_w = map.number("thermal_resistance_c_per_w");
  return motor;
}

PropellerParams readPropeller(const YamlMap& map) {
  map.allowOnly({"name", "diameter_m", "thrust_coefficient", "torque_coefficient", "inertia_kg_m2", "solidity"});
  return PropellerParams{map.text("name"),         map.number("diameter_m"),    map.number("thrust_coefficient"),
                         map.number("torque_coefficient"), map.number("inertia_kg_m2"), map.number("solidity")};
}

LipoBatteryParams readBattery(const YamlMap& map) {
  map.allowOnly({"name", "cells", "capacity_ah", "open_circuit_voltage", "series_resistance_ohm", "rc_resistance_ohm",
                 "rc_capacitance_f"});
  LipoBatteryParams battery;
  battery.name = map.text("name");
  battery.cells = map.integer("cells");
  battery.capacity_ah = map.number("capacity_ah");
  const YamlMap ocv = map.map("open_circuit_voltage");
  ocv.allowOnly({"soc", "cell_v"});
  battery.ocv_soc = ocv.numbers("soc");
  battery.ocv_cell_v = ocv.numbers("cell_v");
  battery.series_resistance_ohm = map.number("series_resistance_ohm");
  battery.rc_resistance_ohm = map.number("rc_resistance_ohm");
  battery.rc_capacitance_f = map.number("rc_capacitance_f");
  return battery;
}

SensorNoise readSensor(const YamlMap& map, const std::string& unit) {
  const std::string sigma = "sigma_" + unit;
  const std::string resolution = "resolution_" + unit;
  map.allowOnly({sigma.c_str(), resolution.c_str()});
  return SensorNoise{map.number(sigma), map.number(resolution)};
}

BenchParams readBench(const YamlMap& map) {
  map.allowOnly({"air", "sweep_pwm_us", "sensors"});
  BenchParams bench;
  bench.air = readAirConditions(map.map("air"));
  std::tie(bench.sweep_pwm_min_us, bench.sweep_pwm_max_us) = map.range("sweep_pwm_us");
  const YamlMap sensors = map.map("sensors");
  sensors.allowOnly({"load_cell", "current", "voltage", "rpm", "temperature"});
  bench.sensors.thrust_n = readSensor(sensors.map("load_cell"), "n");
  bench.sensors.current_a = readSensor(sensors.map("current"), "a");
  bench.sensors.voltage_v = readSensor(sensors.map("voltage"), "v");
  bench.sensors.rpm = readSensor(sensors.map("rpm"), "rpm");
  bench.sensors.temperature_c = readSensor(sensors.map("temperature"), "c");
  return bench;
}

}  // namespace

SimParams parseSimParamsYaml(const std::string& text, const std::string& source) {
  const YamlMap root = parseYamlDocument(text, source);
  root.allowOnly({"format_version", "esc", "motor", "propeller", "battery", "bench"});
  if (root.integer("format_version") != kFormatVersion) {
    root.fail("format_version", std::to_string(root.integer("format_version")) +
                                    " is not supported (this reader knows " + std::to_string(kFormatVersion) + ")");
  }
  SimParams params;
  params.source = source;
  params.chain.esc = readEsc(root.map("esc"));
  params.chain.motor = readMotor(root.map("motor"));
  params.chain.propeller = readPropeller(root.map("propeller"));
  params.battery = readBattery(root.map("battery"));
  params.bench = readBench(root.map("bench"));
  validateAt(root, params);
  return params;
}

SimParams loadSimParamsFile(const std::string& path) { return parseSimParamsYaml(readTextFile(path), path); }

}  // namespace sim
}  // namespace propulsion_estimator
