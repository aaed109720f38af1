#pragma once

#include <string>

#include "propulsion_estimator/common/input_signal.h"
#include "propulsion_estimator/common/mavros_topics.h"
#include "propulsion_estimator/estimation/estimator_config.h"
#include "propulsion_estimator/onboard/capability.h"
#include "propulsion_estimator/onboard/health_summary.h"
#include "propulsion_estimator/onboard/model_check.h"
#include "propulsion_estimator/onboard/parameter_source.h"

namespace propulsion_estimator {

/// Everything estimator_node reads from its private namespace (documented in docs/node.md).
struct EstimatorNodeParams {
  std::string model;       ///< required: path of the model YAML
  std::string urdf_file;   ///< optional: vehicle description; else robot_description, else no geometry
  std::string tare_file;   ///< optional: where ~tare persists the empty mass ("" = not persisted)
  /// optional (capability/battery/pack_file): where each pack's learned record is kept ("" = not
  /// learned; "{pack_id}" in it: a file per pack). Needs capability/battery/capacity_ah and cells.
  std::string pack_file;
  /// optional (capability/battery/pack_id): the pack flown; "" = BatteryState.serial_number's.
  std::string pack_id;
  std::string battery_topic = kBatteryTopic;    ///< sensor_msgs/BatteryState
  std::string rc_out_topic = kRcOutTopic;       ///< mavros_msgs/RCOut
  std::string imu_topic = kImuTopic;            ///< "" disables
  std::string velocity_topic = kVelocityTopic;  ///< "" disables
  /// Each scalar input's topic (`<name>_topic`, its message type in its ScalarSpec), by
  /// input::index; "" disables one. The barometer's static pressure is always subscribed (the hover
  /// check's vertical speed while no velocity is fresh); the others only when an effect of the
  /// model reads a signal prepared from them.
  input::PerScalar<std::string> input_topics = input::defaultTopics();
  /// ESC telemetry, optional: measured rpm and current per motor and the live model check. Both
  /// are subscribed; whichever the autopilot publishes is used. "" disables one.
  std::string esc_telemetry_topic = kEscTelemetryTopic;  ///< mavros_msgs/ESCTelemetry (ArduPilot)
  std::string esc_status_topic = kEscStatusTopic;        ///< mavros_msgs/ESCStatus (PX4)
  /// Highest rate of ~motors, ~totals and ~payload, Hz, on the RCOut stamps; 0 publishes every
  /// accepted RCOut. Every message is still estimated and averaged. 50 Hz passes MAVROS' usual
  /// rc/out whole, and keeps a 400 Hz stream's cost near roscpp's own (BENCHMARKS.md).
  double publish_rate_hz = 50.0;
  /// Seconds between /diagnostics updates; diagnostic_updater reads the same parameter (and has the
  /// same default), the node ticks it once per period.
  double diagnostic_period_s = 1.0;
  HealthConfig health;  ///< domain_warn_fraction; its input names are the topics
  EstimatorConfig estimator;  ///< the estimator's parameters
  CapabilityConfig capability;  ///< the capability/... parameters
  ModelCheckConfig esc_telemetry;  ///< the esc_telemetry/... parameters (live model check)
  /// Where ~capability's hover mass comes from (esc_telemetry/mass_view): "pwm", the surfaces at
  /// PWM and voltage; or "rpm", the measured rotor speeds through the model's thrust_from_rpm while
  /// every motor's telemetry is fresh (the PWM view otherwise).
  std::string mass_view = "pwm";
};

/// Reads and validates the parameters from `source` (the estimator part against the rotors later,
/// when the vehicle is known). Throws ConfigError naming the parameter (source.where()) for a
/// missing model, a value of the wrong type, an unknown or removed name, or a value out of range.
EstimatorNodeParams readNodeParameters(const ParameterSource& source);

/// Every loaded value, as the node logs it once at start.
std::string describeNodeParameters(const EstimatorNodeParams& params);

}  // namespace propulsion_estimator
