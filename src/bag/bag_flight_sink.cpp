#include "propulsion_estimator/bag/bag_flight_sink.h"

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/Range.h>
#include <sensor_msgs/Temperature.h>

#include <iostream>
#include <limits>

#include "propulsion_estimator/SimTruth.h"
#include "propulsion_estimator/common/input_signal.h"
#include "propulsion_estimator/codecs/esc_telemetry_codec.h"
#include "propulsion_estimator/codecs/rcout_codec.h"

namespace propulsion_estimator {
namespace {

std_msgs::Header header(const ros::Time& stamp, const std::string& frame) {
  std_msgs::Header result;
  result.stamp = stamp;
  result.frame_id = frame;
  return result;
}

geometry_msgs::Quaternion toMsg(const Eigen::Quaterniond& q) {
  geometry_msgs::Quaternion msg;
  msg.x = q.x();
  msg.y = q.y();
  msg.z = q.z();
  msg.w = q.w();
  return msg;
}

geometry_msgs::Vector3 toMsg(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 msg;
  msg.x = v.x();
  msg.y = v.y();
  msg.z = v.z();
  return msg;
}

boost::array<double, 9> diagonal(double sigma) {
  boost::array<double, 9> covariance{};
  covariance[0] = covariance[4] = covariance[8] = sigma * sigma;
  return covariance;
}

}  // namespace

BagFlightSink::BagFlightSink(const std::string& path, rosbag::compression::CompressionType compression) : path_(path) {
  bag_.open(path, rosbag::bagmode::Write);
  bag_.setCompression(compression);
}

BagFlightSink::~BagFlightSink() {
  // A destructor must not throw (it may run while an exception unwinds): report instead. Callers
  // that need to know call close() first.
  try {
    close();
  } catch (const std::exception& e) {
    std::cerr << path_ << ": closing the bag failed: " << e.what() << "\n";
  }
}

void BagFlightSink::close() {
  if (bag_.isOpen()) bag_.close();
}

ros::Time BagFlightSink::stamp(double time_s) { return ros::Time(kSimulatedBagStartSec) + ros::Duration(time_s); }

void BagFlightSink::rcOut(const sim::RcOutSample& sample) {
  RcOutMessage message;
  message.header = header(stamp(sample.time_s), "");
  message.header.seq = rc_out_seq_++;
  message.channels = sample.channels;
  bag_.write(kRcOutTopic, message.header.stamp, encodeRcOut(message));
}

void BagFlightSink::battery(const sim::BatterySample& sample) {
  sensor_msgs::BatteryState msg;
  msg.header = header(stamp(sample.time_s), "");
  msg.voltage = static_cast<float>(sample.voltage_v);
  msg.current = static_cast<float>(sample.current_a);
  // The message's convention for what is not measured: NaN. A power module measures neither the
  // pack's temperature nor its charge; the percentage is the autopilot's estimate, and MAVROS
  // leaves cell_voltage empty when (as from SYS_STATUS) it does not know the cell count.
  msg.temperature = std::numeric_limits<float>::quiet_NaN();
  msg.charge = std::numeric_limits<float>::quiet_NaN();
  msg.capacity = std::numeric_limits<float>::quiet_NaN();
  msg.design_capacity = std::numeric_limits<float>::quiet_NaN();
  msg.percentage = static_cast<float>(sample.percentage);
  msg.power_supply_status = sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_DISCHARGING;
  msg.power_supply_health = sensor_msgs::BatteryState::POWER_SUPPLY_HEALTH_UNKNOWN;
  msg.power_supply_technology = sensor_msgs::BatteryState::POWER_SUPPLY_TECHNOLOGY_LIPO;
  msg.present = true;
  bag_.write(kBatteryTopic, msg.header.stamp, msg);
}

void BagFlightSink::imu(const sim::ImuSample& sample) {
  sensor_msgs::Imu msg;
  msg.header = header(stamp(sample.time_s), "base_link");
  msg.orientation = toMsg(sample.orientation);
  msg.orientation_covariance = diagonal(sample.orientation_sigma_rad);
  msg.angular_velocity = toMsg(sample.angular_velocity_rad_s);
  msg.angular_velocity_covariance = diagonal(sample.angular_velocity_sigma_rad_s);
  msg.linear_acceleration = toMsg(sample.linear_acceleration_m_s2);
  msg.linear_acceleration_covariance = diagonal(sample.linear_acceleration_sigma_m_s2);
  bag_.write(kImuTopic, msg.header.stamp, msg);
}

void BagFlightSink::pose(const sim::PoseSample& sample) {
  geometry_msgs::PoseStamped msg;
  msg.header = header(stamp(sample.time_s), "map");
  msg.pose.position.x = sample.position_m.x();
  msg.pose.position.y = sample.position_m.y();
  msg.pose.position.z = sample.position_m.z();
  msg.pose.orientation = toMsg(sample.orientation);
  bag_.write(kPoseTopic, msg.header.stamp, msg);
}

void BagFlightSink::velocity(const sim::VelocitySample& sample) {
  geometry_msgs::TwistStamped msg;
  msg.header = header(stamp(sample.time_s), "map");
  msg.twist.linear = toMsg(sample.linear_m_s);
  msg.twist.angular = toMsg(sample.angular_rad_s);
  bag_.write(kVelocityTopic, msg.header.stamp, msg);
}

void BagFlightSink::staticPressure(const sim::ScalarSample& sample) {
  sensor_msgs::FluidPressure msg;
  msg.header = header(stamp(sample.time_s), sample.frame_id);
  msg.fluid_pressure = sample.value;
  msg.variance = sample.sigma * sample.sigma;
  bag_.write(input::spec(input::Scalar::kStaticPressure).topic, msg.header.stamp, msg);
}

void BagFlightSink::airTemperature(const sim::ScalarSample& sample) {
  writeTemperature(input::spec(input::Scalar::kAirTemperature).topic, sample);
}

void BagFlightSink::rangefinder(const sim::RangeSample& sample) {
  sensor_msgs::Range msg;
  msg.header = header(stamp(sample.time_s), "rangefinder");
  msg.radiation_type = sensor_msgs::Range::INFRARED;
  msg.field_of_view = static_cast<float>(sample.field_of_view_rad);
  msg.min_range = static_cast<float>(sample.min_range_m);
  msg.max_range = static_cast<float>(sample.max_range_m);
  msg.range = static_cast<float>(sample.range_m);
  bag_.write(input::spec(input::Scalar::kRangefinder).topic, msg.header.stamp, msg);
}

void BagFlightSink::motorTemperature(const sim::ScalarSample& sample) {
  writeTemperature(input::spec(input::Scalar::kMotorTemperature).topic, sample);
}

void BagFlightSink::writeTemperature(const char* topic, const sim::ScalarSample& sample) {
  sensor_msgs::Temperature msg;
  msg.header = header(stamp(sample.time_s), sample.frame_id);
  msg.temperature = sample.value;
  msg.variance = sample.sigma * sample.sigma;
  bag_.write(topic, msg.header.stamp, msg);
}

void BagFlightSink::escTelemetry(const sim::EscTelemetrySample& sample) {
  // MAVROS stamps the message and every item it refreshes with the time it received them.
  const ros::Time time = stamp(sample.time_s);
  EscTelemetry message;
  message.stamp_s = time.toSec();
  for (const sim::EscReading& reading : sample.escs) {
    message.escs.push_back({time.toSec(), reading.rpm, reading.current_a, reading.voltage_v, reading.temperature_c,
                            reading.count});
  }
  bag_.write(sample.px4 ? kEscStatusTopic : kEscTelemetryTopic, time, encodeEscTelemetry(message, sample.px4));
}

void BagFlightSink::truth(const sim::TruthSample& sample) {
  SimTruth msg;
  msg.header = header(stamp(sample.time_s), "base_link");
  msg.total_mass_kg = sample.total_mass_kg;
  msg.payload_mass_kg = sample.payload_mass_kg;
  msg.cable_tension_n = sample.cable_tension_n;
  msg.height_m = sample.height_m;
  msg.vertical_speed_m_s = sample.vertical_speed_m_s;
  msg.air_density_kg_m3 = sample.air_density_kg_m3;
  msg.density_ratio = sample.density_ratio;
  msg.battery_voltage_v = sample.battery_voltage_v;
  msg.esc_voltage_v = sample.esc_voltage_v;
  msg.battery_current_a = sample.battery_current_a;
  msg.climb_factor = sample.climb_factor;
  msg.thrust_loss_factor = sample.thrust_loss_factor;
  for (std::size_t k = 0; k < sample.motors.size(); ++k) {
    const sim::MotorTruth& motor = sample.motors[k];
    msg.ground_effect_factor.push_back(motor.ground_effect_factor);
    msg.motor_temperature_c.push_back(motor.winding_temperature_c);
    MotorEstimate estimate;
    estimate.channel = static_cast<std::uint8_t>(k + 1);
    estimate.pwm_us = motor.pwm_us;
    estimate.thrust_n = motor.thrust_n;
    estimate.current_a = motor.current_a;
    estimate.power_w = motor.power_w;
    estimate.efficiency_n_per_w = motor.power_w > 0.0 ? motor.thrust_n / motor.power_w : 0.0;
    estimate.rpm = motor.rpm;
    estimate.in_domain = motor.in_bench_range;
    // The truth is not a measurement: no ESC telemetry beside it.
    estimate.measured_rpm = estimate.measured_current_a = std::numeric_limits<double>::quiet_NaN();
    estimate.rpm_ratio = estimate.current_ratio = std::numeric_limits<double>::quiet_NaN();
    msg.motors.push_back(estimate);
  }
  bag_.write(kSimTruthTopic, msg.header.stamp, msg);
}

}  // namespace propulsion_estimator
