#include "propulsion_estimator/onboard/node_parameters.h"

#include <cmath>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace {

// Typed reads that refuse a parameter of the wrong type instead of silently keeping the default.
class ParamReader {
 public:
  explicit ParamReader(const ParameterSource& source) : source_(source) {}

  template <typename T>
  void optional(const std::string& name, T* value) {
    known_.insert(name);
    if (source_.has(name) && !source_.get(name, value)) {
      throw ConfigError(source_.where(name) + ": wrong type, expected " + typeName(*value));
    }
  }

  void required(const std::string& name, std::string* value) {
    if (!source_.has(name)) throw ConfigError(source_.where(name) + ": required parameter is not set");
    optional(name, value);
  }

  // A parameter without default: unset when absent.
  template <typename T>
  void optional(const std::string& name, std::optional<T>* value) {
    known_.insert(name);
    if (!source_.has(name)) return;
    T read{};
    optional(name, &read);
    *value = read;
  }

  // A parameter no longer read: refused with why, not left silently without effect.
  void removed(const std::string& name, const std::string& why) const {
    if (source_.has(name)) throw ConfigError(source_.where(name) + ": " + why);
  }

  std::string where(const std::string& name) const { return source_.where(name); }

  // A misspelt parameter would otherwise leave its default silently in force.
  void refuseUnknown() const {
    for (const std::string& name : source_.names()) {
      if (known_.count(name) == 0) {
        throw ConfigError(source_.where(name) + ": unknown parameter (see the README's parameter table)");
      }
    }
  }

 private:
  static const char* typeName(const std::string&) { return "a string"; }
  static const char* typeName(double) { return "a number"; }
  static const char* typeName(bool) { return "true or false"; }
  static const char* typeName(int) { return "an integer"; }
  static const char* typeName(const std::vector<int>&) { return "a list of integers"; }
  static const char* typeName(const std::vector<double>&) { return "a list of numbers"; }

  const ParameterSource& source_;
  std::set<std::string> known_;
};

// The node's own parameters: the model, files, topics.
void readFilesAndTopics(ParamReader& read, EstimatorNodeParams* params) {
  EstimatorNodeParams& p = *params;
  read.required("model", &p.model);
  read.optional("urdf_file", &p.urdf_file);
  read.optional("tare_file", &p.tare_file);
  read.optional("capability/battery/pack_file", &p.pack_file);
  read.optional("capability/battery/pack_id", &p.pack_id);
  read.optional("battery_topic", &p.battery_topic);
  read.optional("rc_out_topic", &p.rc_out_topic);
  read.optional("imu_topic", &p.imu_topic);
  read.optional("velocity_topic", &p.velocity_topic);
  for (input::Scalar scalar : input::kAllScalars) {
    read.optional(input::topicParameter(scalar), &p.input_topics[input::index(scalar)]);
  }
  read.optional("esc_telemetry_topic", &p.esc_telemetry_topic);
  read.optional("esc_status_topic", &p.esc_status_topic);
  read.optional("domain_warn_fraction", &p.health.domain_warn_fraction);

}

// The estimator's parameters, and publish_rate_hz read among them.
void readEstimatorConfig(ParamReader& read, EstimatorConfig* config, double* publish_rate_hz) {
  EstimatorConfig& c = *config;
  read.optional("motor_channels", &c.motor_channels);
  read.optional("disarmed_pwm_max_us", &c.disarmed_pwm_max_us);
  read.optional("battery_timeout_s", &c.battery_timeout_s);
  read.optional("imu/timeout_s", &c.imu_timeout_s);
  read.optional("imu/compensate_tilt", &c.compensate_tilt);
  read.optional("imu/compensate_acceleration", &c.compensate_acceleration);
  read.optional("imu/accel_filter_s", &c.accel_filter_s);
  read.optional("imu/accel_bias_filter_s", &c.accel_bias_filter_s);
  read.optional("velocity/timeout_s", &c.velocity_timeout_s);
  for (input::Scalar scalar : input::kAllScalars) {
    read.optional(input::timeoutParameter(scalar), &c.input_timeout_s[input::index(scalar)]);
  }
  read.optional("publish_rate_hz", publish_rate_hz);
  read.optional("clock_jump_reset_s", &c.clock_jump_reset_s);
  read.optional("max_stamp_ahead_s", &c.max_stamp_ahead_s);
  read.optional("empty_mass_kg", &c.empty_mass_kg);
  read.optional("hover/window_s", &c.hover.window_s);
  read.optional("hover/min_window_fill", &c.hover.min_window_fill);
  read.optional("hover/max_thrust_rel_std", &c.hover.max_thrust_rel_std);
  read.optional("hover/max_tilt_deg", &c.hover.max_tilt_deg);
  read.optional("hover/max_vertical_speed_m_s", &c.hover.max_vertical_speed_m_s);
  read.optional("hover/max_vertical_accel_m_s2", &c.hover.max_vertical_accel_m_s2);
  read.optional("hover/min_mass_kg", &c.hover.min_mass_kg);
  read.optional("payload/averaging_window_s", &c.payload.averaging_window_s);
  int min_samples = static_cast<int>(c.payload.min_samples);
  read.optional("payload/min_samples", &min_samples);
  if (min_samples < 0) throw ConfigError(read.where("payload/min_samples") + ": must not be negative");
  c.payload.min_samples = static_cast<std::size_t>(min_samples);
  read.optional("payload/episode_gap_s", &c.payload.episode_gap_s);
}

void readCapabilityConfig(ParamReader& read, CapabilityConfig* config) {
  CapabilityConfig& k = *config;
  read.optional("capability/rate_hz", &k.rate_hz);
  read.optional("capability/pwm_max_us", &k.pwm_max_us);
  read.optional("capability/min_thrust_to_weight", &k.min_thrust_to_weight);
  read.optional("capability/reserve_s", &k.reserve_s);
  read.optional("capability/battery/capacity_ah", &k.capacity_ah);
  read.optional("capability/battery/cells", &k.cells);
  read.removed("capability/battery/usable_fraction",
               "removed: the usable charge follows from the open-circuit curve, the internal resistance and the "
               "hover current (docs/capability.md); give the loaded cut-off as capability/battery/cell_cutoff_v");
  read.removed("capability/battery/cell_full_v",
               "removed: the full voltage is the open-circuit curve's (capability/battery/chemistry or ocv_table)");
  read.optional("capability/battery/chemistry", &k.chemistry);
  read.optional("capability/battery/ocv_table/soc", &k.ocv_table_soc);
  read.optional("capability/battery/ocv_table/cell_v", &k.ocv_table_cell_v);
  read.optional("capability/battery/cell_cutoff_v", &k.cell_cutoff_v);
  read.optional("capability/battery/temperature_c", &k.temperature_c);
  std::string percentage = percentageModeName(k.percentage);
  read.optional("capability/battery/percentage", &percentage);
  k.percentage = percentageModeFromName(percentage);
  read.optional("capability/motor_health/block_s", &k.motor_health.block_s);
  read.optional("capability/motor_health/window_s", &k.motor_health.window_s);
  read.optional("capability/motor_health/max_gap", &k.motor_health.max_gap);
  read.optional("capability/motor_health/healthy_gap_std", &k.motor_health.healthy_gap_std);
}

// What depends on several parameters, checked once all are read.
void validateNodeParams(const ParamReader& read, EstimatorNodeParams* params) {
  EstimatorNodeParams& p = *params;
  p.health.battery_input = p.battery_topic;
  p.health.rc_out_input = p.rc_out_topic;
  p.health.signal_sources.battery = p.battery_topic;
  p.health.signal_sources.velocity = p.velocity_topic;
  p.health.signal_sources.imu = p.imu_topic;
  p.health.signal_sources.inputs = p.input_topics;
  p.health.validate();
  p.capability.validate();
  if (!p.pack_file.empty() && !p.capability.battery()) {
    throw ConfigError(read.where("capability/battery/pack_file") +
                      ": needs the pack it learns, capability/battery/capacity_ah and cells");
  }
  p.esc_telemetry.validate();
  if (p.mass_view != "pwm" && p.mass_view != "rpm") {
    throw ConfigError(read.where("esc_telemetry/mass_view") + ": '" + p.mass_view + "' is not pwm or rpm");
  }
  // 0 would tick the diagnostics timer without pause.
  if (!(p.diagnostic_period_s > 0.0) || !std::isfinite(p.diagnostic_period_s)) {
    throw ConfigError(read.where("diagnostic_period") + ": must be a positive number of seconds, got " +
                      formatNumber(p.diagnostic_period_s));
  }
  if (!(p.publish_rate_hz >= 0.0) || !std::isfinite(p.publish_rate_hz)) {
    throw ConfigError(read.where("publish_rate_hz") + ": must be 0 (every message) or a positive rate in Hz, got " +
                      formatNumber(p.publish_rate_hz));
  }
}

// The live model check's parameters (esc_telemetry/...).
void readModelCheckConfig(ParamReader& read, ModelCheckConfig* config) {
  ModelCheckConfig& m = *config;
  read.optional("esc_telemetry/stale_after_s", &m.stale_after_s);
  read.optional("esc_telemetry/window_s", &m.window_s);
  read.optional("esc_telemetry/min_hover_s", &m.min_hover_s);
  read.optional("esc_telemetry/rpm_tolerance", &m.rpm_tolerance);
  read.optional("esc_telemetry/current_tolerance", &m.current_tolerance);
  read.optional("esc_telemetry/supply_tolerance", &m.supply_tolerance);
  read.optional("esc_telemetry/supply_memory_s", &m.supply_memory_s);
  read.optional("esc_telemetry/supply_voltage_sigma_v", &m.supply_voltage_sigma_v);
  read.optional("esc_telemetry/supply_max_rel_std", &m.supply_max_rel_std);
  read.optional("esc_telemetry/apply_supply_resistance", &m.apply_supply_resistance);
}

}  // namespace

namespace {

// " static_pressure_topic /mavros/imu/static_pressure (timeout_s 1), ...": each scalar input's.
std::string inputTopics(const EstimatorNodeParams& p) {
  std::ostringstream text;
  for (input::Scalar scalar : input::kAllScalars) {
    const std::string& topic = p.input_topics[input::index(scalar)];
    text << (scalar == input::kAllScalars.front() ? " " : ", ") << input::topicParameter(scalar) << " "
         << (topic.empty() ? "(disabled)" : topic) << " (timeout_s " << p.estimator.inputTimeoutS(scalar) << ")";
  }
  return text.str();
}

}  // namespace

std::string describeNodeParameters(const EstimatorNodeParams& p) {
  const EstimatorConfig& c = p.estimator;
  const CapabilityConfig& k = p.capability;
  const ModelCheckConfig& m = p.esc_telemetry;
  std::ostringstream channels;
  for (std::size_t i = 0; i < c.motor_channels.size(); ++i) channels << (i ? ", " : "") << c.motor_channels[i];
  std::ostringstream text;
  text << "propulsion_estimator parameters:"
                  << "\n  model: " << p.model << "\n  urdf_file: " << (p.urdf_file.empty() ? "(none)" : p.urdf_file)
                  << "\n  tare_file: " << (p.tare_file.empty() ? "(not persisted)" : p.tare_file)
                  << "\n  battery_topic: " << p.battery_topic << "\n  rc_out_topic: " << p.rc_out_topic
                  << "\n  imu_topic: " << (p.imu_topic.empty() ? "(disabled)" : p.imu_topic)
                  << "\n  velocity_topic: " << (p.velocity_topic.empty() ? "(disabled)" : p.velocity_topic)
                  << "\n  motor_channels: [" << channels.str() << "]"
                  << "\n  disarmed_pwm_max_us: " << c.disarmed_pwm_max_us
                  << "\n  battery_timeout_s: " << c.battery_timeout_s
                  << "\n  empty_mass_kg: " << (c.empty_mass_kg ? std::to_string(*c.empty_mass_kg) : "(not set)")
                  << "\n  imu: timeout_s " << c.imu_timeout_s << ", compensate_tilt " << c.compensate_tilt
                  << ", compensate_acceleration " << c.compensate_acceleration << ", accel_filter_s "
                  << c.accel_filter_s << ", accel_bias_filter_s " << c.accel_bias_filter_s
                  << "\n  velocity: timeout_s " << c.velocity_timeout_s
                  << "\n  scalar inputs (static_pressure always, the others when the model's effects read them):"
                  << inputTopics(p)
                  << "\n  hover: window_s " << c.hover.window_s << ", min_window_fill " << c.hover.min_window_fill
                  << ", max_thrust_rel_std " << c.hover.max_thrust_rel_std << ", max_tilt_deg "
                  << c.hover.max_tilt_deg << ", max_vertical_speed_m_s " << c.hover.max_vertical_speed_m_s
                  << ", max_vertical_accel_m_s2 " << c.hover.max_vertical_accel_m_s2 << ", min_mass_kg "
                  << c.hover.min_mass_kg << "\n  payload: averaging_window_s " << c.payload.averaging_window_s
                  << ", min_samples " << c.payload.min_samples << ", episode_gap_s " << c.payload.episode_gap_s
                  << "\n  publish_rate_hz: "
                  << (p.publish_rate_hz > 0.0 ? formatNumber(p.publish_rate_hz) : std::string("0 (every message)"))
                  << ", clock_jump_reset_s: " << c.clock_jump_reset_s
                  << ", max_stamp_ahead_s: " << c.max_stamp_ahead_s
                  << ", domain_warn_fraction: " << p.health.domain_warn_fraction
                  << ", diagnostic_period: " << p.diagnostic_period_s
                  << "\n  capability: rate_hz " << k.rate_hz << ", pwm_max_us "
                  << (k.pwm_max_us ? std::to_string(*k.pwm_max_us) : "(the model's domain maximum)")
                  << ", min_thrust_to_weight " << k.min_thrust_to_weight << ", reserve_s " << k.reserve_s
                  << "\n  capability/battery: capacity_ah "
                  << (k.capacity_ah ? std::to_string(*k.capacity_ah) : "(not set: no endurance)") << ", cells "
                  << (k.cells ? std::to_string(*k.cells) : "(not set)") << ", chemistry " << k.chemistry
                  << (k.ocv_table_soc.empty() ? "" : " (replaced by ocv_table, " + std::to_string(k.ocv_table_soc.size()) + " points)")
                  << ", cell_cutoff_v " << k.cell_cutoff_v << ", percentage " << percentageModeName(k.percentage)
                  << ", temperature_c " << (k.temperature_c ? std::to_string(*k.temperature_c) : "(BatteryState's, else unknown)")
                  << ", pack_file " << (p.pack_file.empty() ? "(not learned)" : p.pack_file) << ", pack_id "
                  << (p.pack_id.empty() ? "(BatteryState.serial_number)" : p.pack_id)
                  << "\n  capability/motor_health: block_s " << k.motor_health.block_s << ", window_s "
                  << k.motor_health.window_s << ", max_gap " << k.motor_health.max_gap
                  << ", healthy_gap_std " << k.motor_health.healthy_gap_std
                  << "\n  esc_telemetry_topic: " << (p.esc_telemetry_topic.empty() ? "(disabled)" : p.esc_telemetry_topic)
                  << ", esc_status_topic: " << (p.esc_status_topic.empty() ? "(disabled)" : p.esc_status_topic)
                  << "\n  esc_telemetry: stale_after_s " << m.stale_after_s << ", window_s " << m.window_s
                  << ", min_hover_s " << m.min_hover_s << ", rpm_tolerance " << m.rpm_tolerance
                  << ", current_tolerance " << m.current_tolerance << ", supply_tolerance " << m.supply_tolerance
                  << ", supply_memory_s " << m.supply_memory_s << ", supply_voltage_sigma_v "
                  << m.supply_voltage_sigma_v << ", supply_max_rel_std " << m.supply_max_rel_std
                  << ", apply_supply_resistance " << m.apply_supply_resistance << ", mass_view " << p.mass_view;
  return text.str();
}

EstimatorNodeParams readNodeParameters(const ParameterSource& source) {
  ParamReader read(source);
  EstimatorNodeParams p;
  readFilesAndTopics(read, &p);
  readEstimatorConfig(read, &p.estimator, &p.publish_rate_hz);
  readCapabilityConfig(read, &p.capability);
  readModelCheckConfig(read, &p.esc_telemetry);
  read.optional("esc_telemetry/mass_view", &p.mass_view);
  read.optional("diagnostic_period", &p.diagnostic_period_s);  // diagnostic_updater reads it too
  read.refuseUnknown();
  validateNodeParams(read, &p);
  return p;
}

}  // namespace propulsion_estimator
