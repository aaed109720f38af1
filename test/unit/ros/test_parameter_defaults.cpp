#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "parameter_template.h"
#include "propulsion_estimator/ros/estimator_params.h"

namespace pe = propulsion_estimator;

// The template shows the defaults the node applies when a parameter is not set, so that loading
// it changes nothing.
TEST(ParameterDefaults, TemplateHoldsTheNodesDefaults) {
  const ParameterTemplate file = loadParameterTemplate();
  const pe::EstimatorNodeParams node;
  const pe::EstimatorConfig& c = node.estimator;
  std::set<std::string> checked;
  const auto value = [&](const std::string& name) {
    checked.insert(name);
    EXPECT_EQ(file.values.count(name), 1u) << name << " is not set in the template";
    return file.values.count(name) ? file.values.at(name) : YAML::Node();
  };
  const auto number = [&](const std::string& name) { return value(name).as<double>(-1.0); };
  const auto text = [&](const std::string& name) { return value(name).as<std::string>("(none)"); };
  const auto flag = [&](const std::string& name) { return value(name).as<std::string>("(none)") == "true"; };

  EXPECT_EQ(value("motor_channels").as<std::vector<int>>(std::vector<int>{}), c.motor_channels);
  EXPECT_EQ(text("urdf_file"), node.urdf_file);
  EXPECT_EQ(text("tare_file"), node.tare_file);
  EXPECT_EQ(text("battery_topic"), node.battery_topic);
  EXPECT_EQ(text("rc_out_topic"), node.rc_out_topic);
  EXPECT_EQ(text("imu_topic"), node.imu_topic);
  EXPECT_EQ(text("velocity_topic"), node.velocity_topic);
  EXPECT_EQ(number("disarmed_pwm_max_us"), c.disarmed_pwm_max_us);
  EXPECT_EQ(number("battery_timeout_s"), c.battery_timeout_s);
  EXPECT_EQ(number("imu/timeout_s"), c.imu_timeout_s);
  EXPECT_EQ(flag("imu/compensate_tilt"), c.compensate_tilt);
  EXPECT_EQ(flag("imu/compensate_acceleration"), c.compensate_acceleration);
  EXPECT_EQ(number("imu/accel_filter_s"), c.accel_filter_s);
  EXPECT_EQ(number("imu/accel_bias_filter_s"), c.accel_bias_filter_s);
  EXPECT_EQ(number("velocity/timeout_s"), c.velocity_timeout_s);
  EXPECT_EQ(text("static_pressure_topic"), node.input_topics[pe::input::index(pe::input::Scalar::kStaticPressure)]);
  EXPECT_EQ(text("air_temperature_topic"), node.input_topics[pe::input::index(pe::input::Scalar::kAirTemperature)]);
  EXPECT_EQ(text("rangefinder_topic"), node.input_topics[pe::input::index(pe::input::Scalar::kRangefinder)]);
  EXPECT_EQ(text("motor_temperature_topic"), node.input_topics[pe::input::index(pe::input::Scalar::kMotorTemperature)]);
  EXPECT_EQ(number("static_pressure/timeout_s"), c.input_timeout_s[pe::input::index(pe::input::Scalar::kStaticPressure)]);
  EXPECT_EQ(number("air_temperature/timeout_s"), c.input_timeout_s[pe::input::index(pe::input::Scalar::kAirTemperature)]);
  EXPECT_EQ(number("rangefinder/timeout_s"), c.input_timeout_s[pe::input::index(pe::input::Scalar::kRangefinder)]);
  EXPECT_EQ(number("motor_temperature/timeout_s"), c.input_timeout_s[pe::input::index(pe::input::Scalar::kMotorTemperature)]);
  EXPECT_EQ(number("hover/window_s"), c.hover.window_s);
  EXPECT_EQ(number("hover/min_window_fill"), c.hover.min_window_fill);
  EXPECT_EQ(number("hover/max_thrust_rel_std"), c.hover.max_thrust_rel_std);
  EXPECT_EQ(number("hover/max_tilt_deg"), c.hover.max_tilt_deg);
  EXPECT_EQ(number("hover/max_vertical_speed_m_s"), c.hover.max_vertical_speed_m_s);
  EXPECT_EQ(number("hover/max_vertical_accel_m_s2"), c.hover.max_vertical_accel_m_s2);
  EXPECT_EQ(number("hover/min_mass_kg"), c.hover.min_mass_kg);
  EXPECT_EQ(number("payload/averaging_window_s"), c.payload.averaging_window_s);
  EXPECT_EQ(number("payload/min_samples"), static_cast<double>(c.payload.min_samples));
  EXPECT_EQ(number("payload/episode_gap_s"), c.payload.episode_gap_s);
  EXPECT_EQ(number("publish_rate_hz"), node.publish_rate_hz);
  EXPECT_EQ(number("clock_jump_reset_s"), c.clock_jump_reset_s);
  EXPECT_EQ(number("max_stamp_ahead_s"), c.max_stamp_ahead_s);
  EXPECT_EQ(number("domain_warn_fraction"), node.health.domain_warn_fraction);
  EXPECT_EQ(number("diagnostic_period"), node.diagnostic_period_s);
  EXPECT_EQ(node.diagnostic_period_s, 1.0);  // diagnostic_updater's own default
  EXPECT_FALSE(c.empty_mass_kg.has_value());     // commented in the template: not set
  const pe::CapabilityConfig& k = node.capability;
  EXPECT_EQ(number("capability/rate_hz"), k.rate_hz);
  EXPECT_EQ(number("capability/min_thrust_to_weight"), k.min_thrust_to_weight);
  EXPECT_EQ(number("capability/reserve_s"), k.reserve_s);
  EXPECT_EQ(text("capability/battery/chemistry"), k.chemistry);
  EXPECT_EQ(text("capability/battery/percentage"), pe::percentageModeName(k.percentage));
  EXPECT_EQ(number("capability/battery/cell_cutoff_v"), k.cell_cutoff_v);
  EXPECT_EQ(number("capability/motor_health/block_s"), k.motor_health.block_s);
  EXPECT_EQ(number("capability/motor_health/window_s"), k.motor_health.window_s);
  EXPECT_EQ(number("capability/motor_health/max_gap"), k.motor_health.max_gap);
  EXPECT_EQ(number("capability/motor_health/healthy_gap_std"), k.motor_health.healthy_gap_std);
  EXPECT_EQ(text("esc_telemetry_topic"), node.esc_telemetry_topic);
  EXPECT_EQ(text("esc_status_topic"), node.esc_status_topic);
  const pe::ModelCheckConfig& m = node.esc_telemetry;
  EXPECT_EQ(number("esc_telemetry/stale_after_s"), m.stale_after_s);
  EXPECT_EQ(number("esc_telemetry/window_s"), m.window_s);
  EXPECT_EQ(number("esc_telemetry/min_hover_s"), m.min_hover_s);
  EXPECT_EQ(number("esc_telemetry/rpm_tolerance"), m.rpm_tolerance);
  EXPECT_EQ(number("esc_telemetry/current_tolerance"), m.current_tolerance);
  EXPECT_EQ(number("esc_telemetry/supply_tolerance"), m.supply_tolerance);
  EXPECT_EQ(number("esc_telemetry/supply_memory_s"), m.supply_memory_s);
  EXPECT_EQ(number("esc_telemetry/supply_voltage_sigma_v"), m.supply_voltage_sigma_v);
  EXPECT_EQ(number("esc_telemetry/supply_max_rel_std"), m.supply_max_rel_std);
  EXPECT_EQ(flag("esc_telemetry/apply_supply_resistance"), m.apply_supply_resistance);
  EXPECT_EQ(text("esc_telemetry/mass_view"), node.mass_view);
  // Commented in the template: not set.
  EXPECT_FALSE(k.pwm_max_us.has_value());
  EXPECT_FALSE(k.capacity_ah.has_value());
  EXPECT_FALSE(k.cells.has_value());

  std::set<std::string> set_in_file;
  for (const auto& [name, node_value] : file.values) set_in_file.insert(name);
  EXPECT_EQ(checked, set_in_file) << "a parameter of the template is not compared with its default here";
}
