#include "propulsion_estimator/sim/flight/ulog_flight_sink.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "propulsion_estimator/logs/autopilot_frames.h"

namespace propulsion_estimator {
namespace sim {
namespace {

// msg_ids of the topics written.
enum Id : std::uint16_t { kOutputs, kBattery, kAttitude, kAccel, kPosition, kAir, kRangeDown, kRangeFront, kEsc };

constexpr int kEscs = 8;
constexpr int kMotor1 = 101;  // esc_report.actuator_function of the first motor

}  // namespace

UlogFlightSink::UlogFlightSink(UlogLayout layout, double pwm_min_us, double pwm_max_us, double boot_s)
    : layout_(layout),
      pwm_min_us_(pwm_min_us),
      pwm_max_us_(pwm_max_us),
      boot_s_(boot_s),
      writer_(static_cast<std::uint64_t>(std::llround(boot_s * 1e6))) {
  const bool old = layout == UlogLayout::kPx4v1_12;
  writer_.flagBits();
  writer_.info("char[9] sys_name", "PX4 (sim)");
  writer_.info("char[7] ver_sw_release", old ? "v1.12.3" : "v1.14.0");
  if (old) {
    writer_.format("actuator_outputs:uint64_t timestamp;uint32_t noutputs;float[16] output;uint8_t[4] _padding0;");
    writer_.format("battery_status:uint64_t timestamp;float voltage_v;float voltage_filtered_v;float current_a;"
                   "float current_filtered_a;float remaining;uint8_t connected;uint8_t[3] _padding0;");
    writer_.format("sensor_combined:uint64_t timestamp;float[3] gyro_rad;uint32_t gyro_integral_dt;"
                   "int32_t accelerometer_timestamp_relative;float[3] accelerometer_m_s2;");
  } else {
    writer_.format("actuator_motors:uint64_t timestamp;uint64_t timestamp_sample;uint16_t reversible_flags;"
                   "float[12] control;uint8_t[6] _padding0;");
    writer_.format("battery_status:uint64_t timestamp;uint8_t connected;uint8_t[3] _padding0;float voltage_v;"
                   "float current_a;float current_average_a;float remaining;");
    writer_.format("vehicle_acceleration:uint64_t timestamp;uint64_t timestamp_sample;float[3] xyz;uint8_t[4] _padding0;");
  }
  writer_.format("vehicle_attitude:uint64_t timestamp;uint64_t timestamp_sample;float[4] q;float[4] delta_q_reset;"
                 "uint8_t quat_reset_counter;uint8_t[7] _padding0;");
  writer_.format("vehicle_local_position:uint64_t timestamp;bool xy_valid;bool z_valid;bool v_xy_valid;bool v_z_valid;"
                 "float x;float y;float z;float vx;float vy;float vz;");
  writer_.format(std::string("vehicle_air_data:uint64_t timestamp;uint64_t timestamp_sample;uint32_t baro_device_id;"
                             "float baro_alt_meter;float ") +
                 (old ? "baro_temp_celcius" : "ambient_temperature") + ";float baro_pressure_pa;float rho;");
  writer_.format("distance_sensor:uint64_t timestamp;uint32_t device_id;float min_distance;float max_distance;"
                 "float current_distance;float variance;int8_t signal_quality;uint8_t type;uint8_t orientation;"
                 "uint8_t _padding0;");
  // The nested type after its user, as a format may come in any order.
  writer_.format("esc_status:uint64_t timestamp;uint16_t counter;uint8_t esc_count;uint8_t esc_connectiontype;"
                 "uint8_t esc_online_flags;uint8_t esc_armed_flags;uint8_t[2] _padding0;esc_report[8] esc;");
  writer_.format(std::string("esc_report:uint64_t timestamp;uint32_t esc_errorcount;int32_t esc_rpm;float esc_voltage;"
                             "float esc_current;") +
                 (old ? "float esc_temperature;float motor_temperature;"
                      : "float motor_temperature;float esc_temperature;uint8_t actuator_function;uint8_t[3] _padding0;"));
  writer_.subscribe(kOutputs, old ? "actuator_outputs" : "actuator_motors");
  writer_.subscribe(kBattery, "battery_status");
  writer_.subscribe(kAttitude, "vehicle_attitude");
  writer_.subscribe(kAccel, old ? "sensor_combined" : "vehicle_acceleration");
  writer_.subscribe(kPosition, "vehicle_local_position");
  writer_.subscribe(kAir, "vehicle_air_data");
  writer_.subscribe(kRangeDown, "distance_sensor", old ? 0 : 1);
  if (!old) writer_.subscribe(kRangeFront, "distance_sensor", 0);
  writer_.subscribe(kEsc, "esc_status");
}

std::uint64_t UlogFlightSink::stamp(double time_s) const {
  return static_cast<std::uint64_t>(std::llround((boot_s_ + time_s) * 1e6));
}

void UlogFlightSink::rcOut(const RcOutSample& sample) {
  ulog::Payload payload;
  payload.put(stamp(sample.time_s));
  if (layout_ == UlogLayout::kPx4v1_12) {
    payload.put(static_cast<std::uint32_t>(sample.channels.size()));
    for (int k = 0; k < 16; ++k) {
      payload.put(k < static_cast<int>(sample.channels.size()) ? static_cast<float>(sample.channels[k]) : 0.0f);
    }
    payload.zeros(4);
  } else {
    payload.put(stamp(sample.time_s)).put<std::uint16_t>(0);
    for (int k = 0; k < 12; ++k) {
      const double pwm = k < static_cast<int>(sample.channels.size()) ? sample.channels[k] : 0.0;
      // Below the range the motors are stopped: PX4 logs NaN.
      payload.put(pwm < pwm_min_us_ ? NAN : static_cast<float>((pwm - pwm_min_us_) / (pwm_max_us_ - pwm_min_us_)));
    }
    // The trailing padding left out, as PX4's logger does.
  }
  writer_.data(kOutputs, payload);
}

void UlogFlightSink::battery(const BatterySample& sample) {
  ulog::Payload payload;
  payload.put(stamp(sample.time_s));
  const auto volts = static_cast<float>(sample.voltage_v);
  const auto amps = static_cast<float>(sample.current_a);
  if (layout_ == UlogLayout::kPx4v1_12) {
    payload.put(volts).put(volts).put(amps).put(amps).put(static_cast<float>(sample.percentage)).put<std::uint8_t>(1).zeros(3);
  } else {
    payload.put<std::uint8_t>(1).zeros(3).put(volts).put(amps).put(amps).put(static_cast<float>(sample.percentage));
  }
  writer_.data(kBattery, payload);
}

void UlogFlightSink::imu(const ImuSample& sample) {
  const std::uint64_t t = stamp(sample.time_s);
  const Eigen::Vector3d& flu = sample.linear_acceleration_m_s2;
  const Eigen::Vector3f frd(static_cast<float>(flu.x()), static_cast<float>(-flu.y()), static_cast<float>(-flu.z()));
  ulog::Payload accel;
  accel.put(t);
  if (layout_ == UlogLayout::kPx4v1_12) {
    const Eigen::Vector3d& w = sample.angular_velocity_rad_s;
    accel.put(static_cast<float>(w.x())).put(static_cast<float>(-w.y())).put(static_cast<float>(-w.z()));
    accel.put<std::uint32_t>(4000).put<std::int32_t>(0).put(frd.x()).put(frd.y()).put(frd.z());
  } else {
    accel.put(t).put(frd.x()).put(frd.y()).put(frd.z()).zeros(4);
  }
  writer_.data(kAccel, accel);
  const Eigen::Quaterniond q = swapNedEnuFrdFlu(sample.orientation);
  ulog::Payload attitude;
  attitude.put(t).put(t);
  for (const double c : {q.w(), q.x(), q.y(), q.z()}) attitude.put(static_cast<float>(c));
  attitude.zeros(4 * 4 + 1 + 7);
  writer_.data(kAttitude, attitude);
}

void UlogFlightSink::pose(const PoseSample& sample) { altitude_m_ = sample.position_m.z(); }

void UlogFlightSink::velocity(const VelocitySample& sample) {
  const Eigen::Vector3d& v = sample.linear_m_s;
  ulog::Payload payload;
  payload.put(stamp(sample.time_s)).put<std::uint8_t>(0).put<std::uint8_t>(1).put<std::uint8_t>(0).put<std::uint8_t>(1);
  payload.put(0.0f).put(0.0f).put(static_cast<float>(-altitude_m_));
  payload.put(static_cast<float>(v.y())).put(static_cast<float>(v.x())).put(static_cast<float>(-v.z()));
  writer_.data(kPosition, payload);
}

void UlogFlightSink::staticPressure(const ScalarSample& sample) {
  const std::uint64_t t = stamp(sample.time_s);
  ulog::Payload payload;
  payload.put(t).put(t).put<std::uint32_t>(1).put(0.0f).put(static_cast<float>(air_temperature_c_));
  payload.put(static_cast<float>(sample.value)).put(0.0f);
  writer_.data(kAir, payload);
}

void UlogFlightSink::airTemperature(const ScalarSample& sample) { air_temperature_c_ = sample.value; }

void UlogFlightSink::rangefinder(const RangeSample& sample) {
  const auto range = [&](std::uint8_t orientation, float distance) {
    ulog::Payload payload;
    payload.put(stamp(sample.time_s)).put<std::uint32_t>(orientation);
    payload.put(static_cast<float>(sample.min_range_m)).put(static_cast<float>(sample.max_range_m)).put(distance);
    payload.put(0.0f).put<std::int8_t>(100).put<std::uint8_t>(0).put(orientation).zeros(1);
    return payload;
  };
  writer_.data(kRangeDown, range(25, static_cast<float>(sample.range_m)));
  // A forward sensor on instance 0 of the newer layout: the reader must pick the downward one.
  if (layout_ == UlogLayout::kPx4v1_14) writer_.data(kRangeFront, range(0, 3.0f));
}

void UlogFlightSink::escStatus(double time_s, const std::vector<EscReading>& escs, double motor_temperature_c) {
  const bool old = layout_ == UlogLayout::kPx4v1_12;
  ulog::Payload payload;
  const std::uint64_t t = stamp(time_s);
  const int n = std::min(static_cast<int>(escs.size()), kEscs);
  // Online: the ESCs whose telemetry this message carries (none in a temperature-only message).
  const auto online = static_cast<std::uint8_t>((1u << n) - 1u);
  payload.put(t).put<std::uint16_t>(0).put(static_cast<std::uint8_t>(std::max(1, n))).put<std::uint8_t>(0);
  payload.put(online).put(online).zeros(2);
  for (int slot = 0; slot < kEscs; ++slot) {
    // The newer layout says which motor each ESC drives: written in reverse, as a wiring may be.
    const int k = old || slot >= n ? slot : n - 1 - slot;
    const bool reported = k < n;
    const float hottest = k == 0 || std::isnan(motor_temperature_c) ? static_cast<float>(motor_temperature_c) : 0.0f;
    payload.put(t).put<std::uint32_t>(0);
    payload.put<std::int32_t>(reported ? static_cast<std::int32_t>(std::lround(escs[k].rpm)) : 0);
    payload.put(reported ? static_cast<float>(escs[k].voltage_v) : 0.0f);
    payload.put(reported ? static_cast<float>(escs[k].current_a) : 0.0f);
    // esc_temperature, the ESC's own, is a few degrees off the motor's, and is not read.
    if (old) {
      payload.put(hottest - 5.0f).put(hottest);
    } else {
      payload.put(hottest).put(hottest - 5.0f).put(static_cast<std::uint8_t>(kMotor1 + k)).zeros(3);
    }
  }
  writer_.data(kEsc, payload);
}

void UlogFlightSink::motorTemperature(const ScalarSample& sample) { escStatus(sample.time_s, {}, sample.value); }

// The telemetry's messages carry no motor temperature (NaN): the temperature stream keeps its own rate.
void UlogFlightSink::escTelemetry(const EscTelemetrySample& sample) { escStatus(sample.time_s, sample.escs, NAN); }

}  // namespace sim
}  // namespace propulsion_estimator
