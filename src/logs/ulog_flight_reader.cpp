#include "propulsion_estimator/logs/ulog_flight_reader.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/logs/autopilot_frames.h"

namespace propulsion_estimator {
namespace {

// A count, a flag set or a function the log states as a number: a field declared as a float (a
// damaged or foreign format) may hold anything; outside 0..65535 it states none (-1).
int smallInteger(double value) { return value >= 0.0 && value <= 65535.0 ? static_cast<int>(value) : -1; }

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kDownward = 25;  // distance_sensor.orientation: ROTATION_DOWNWARD_FACING

// One pass of one topic: the data messages of topic `name` (instance `instance`, any when -1).
class Topics {
 public:
  explicit Topics(const ulog::File& file) : file_(file) {}

  bool has(const std::string& name, int instance = 0) const { return !ids(name, instance).empty(); }

  void forEach(const std::string& name, int instance, const std::function<void(const ulog::DataMessage&)>& use) const {
    const std::set<std::uint16_t> ids_wanted = ids(name, instance);
    if (ids_wanted.empty()) return;
    // A flag per msg_id: each pass looks at every data message of the log, a million in an hour.
    std::vector<bool> wanted(std::numeric_limits<std::uint16_t>::max() + 1, false);
    for (std::uint16_t id : ids_wanted) wanted[id] = true;
    for (const ulog::DataMessage& message : file_.data()) {
      if (wanted[message.msg_id]) use(message);
    }
  }
  // How many messages forEach(name, instance) gives, to size what they fill.
  std::size_t count(const std::string& name, int instance) const {
    std::size_t n = 0;
    forEach(name, instance, [&n](const ulog::DataMessage&) { ++n; });
    return n;
  }

  // The first of `paths` the format of `name` has.
  std::optional<ulog::Locator> field(const std::string& name, std::initializer_list<const char*> paths) const {
    for (const char* path : paths) {
      if (auto locator = file_.locate(name, path)) return locator;
    }
    return std::nullopt;
  }

 private:
  std::set<std::uint16_t> ids(const std::string& name, int instance) const {
    std::set<std::uint16_t> found;
    for (const auto& [id, subscription] : file_.subscriptions()) {
      if (subscription.name == name && (instance < 0 || subscription.multi_id == instance)) found.insert(id);
    }
    return found;
  }

  const ulog::File& file_;
};

// Reads one log's signals into FlightStreams on the manifest's clock.
class SignalReader {
 public:
  SignalReader(const ulog::File& file, std::uint64_t first_us, const std::string& path, FlightStreams* streams)
      : file_(file), topics_(file), first_us_(first_us), path_(path), streams_(streams) {}

  double time(const ulog::DataMessage& message) const {
    return static_cast<double>(static_cast<std::int64_t>(file_.timestampUs(message) - first_us_)) / 1e6;
  }
  double value(const ulog::DataMessage& message, const ulog::Locator& at) const { return file_.value(message, at); }
  void note(const std::string& line) { streams_->notes.push_back(line); }

  void rcOut(const FlightLogOptions& options) {
    const int motors = options.motors;
    const bool pwm = topics_.has("actuator_outputs");
    const std::string topic = pwm ? "actuator_outputs" : "actuator_motors";
    if (!pwm && !topics_.has(topic)) {
      throw DataError(path_ + ": rc_out: no actuator_outputs or actuator_motors (a required signal)");
    }
    if (!pwm && std::isnan(options.pwm_min_us)) {
      throw ConfigError(path_ + ": rc_out: only actuator_motors (normalised) is logged: give the PWM range it maps onto");
    }
    std::vector<ulog::Locator> outputs;
    for (int k = 0; k < motors; ++k) {
      const std::string name = (pwm ? "output[" : "control[") + std::to_string(k) + "]";
      const auto locator = file_.locate(topic, name);
      if (!locator) {
        throw DataError(path_ + ": rc_out: " + topic + " has no field " + name + ", fewer outputs than the " +
                        std::to_string(motors) + " motors");
      }
      outputs.push_back(*locator);
    }
    topics_.forEach(topic, 0, [&](const ulog::DataMessage& message) {
      RcOutFrame& frame = streams_->rc_out.emplace_back();
      frame.time_s = time(message);
      for (int k = 0; k < motors; ++k) {
        const double output = value(message, outputs[k]);
        // PX4 logs a stopped motor's control as NaN: read as 0 us, an RCOut channel not driven
        // (the estimator takes it as disarmed), not as the range's bottom (idling).
        frame.pwm_us[k] = pwm                  ? output
                          : std::isnan(output) ? 0.0
                                               : options.pwm_min_us + std::clamp(output, 0.0, 1.0) *
                                                                          (options.pwm_max_us - options.pwm_min_us);
      }
    });
    if (streams_->rc_out.empty()) throw DataError(path_ + ": rc_out: no " + topic + " messages (a required signal)");
    note("rc_out: " + topic + "[0]." + (pwm ? "output" : "control") + "[0.." + std::to_string(motors - 1) + "]" +
         (pwm ? " (us)" : " (0..1 mapped onto the PWM range given; NaN, a stopped motor, as 0 us)"));
  }

  void battery() {
    const auto voltage = topics_.field("battery_status", {"voltage_v", "voltage_filtered_v"});
    if (!topics_.has("battery_status") || !voltage) {
      throw DataError(path_ + ": battery: no battery_status with voltage_v (a required signal)");
    }
    const auto current = topics_.field("battery_status", {"current_a", "current_filtered_a"});
    topics_.forEach("battery_status", 0, [&](const ulog::DataMessage& message) {
      const double current_a = current ? value(message, *current) : kNaN;
      streams_->battery.push_back({time(message), value(message, *voltage), current_a == -1.0 ? kNaN : current_a});
    });
    if (streams_->battery.empty()) throw DataError(path_ + ": battery: no battery_status messages (a required signal)");
    note(std::string("battery: battery_status[0].voltage_v") + (current ? ", current_a" : ", no current"));
  }

  void imu() {
    const auto q0 = topics_.field("vehicle_attitude", {"q[0]"});
    const bool combined = topics_.has("sensor_combined", -1);
    const std::string accel_topic = combined ? "sensor_combined" : "vehicle_acceleration";
    const std::string accel_field = combined ? "accelerometer_m_s2" : "xyz";
    const auto a0 = topics_.field(accel_topic, {combined ? "accelerometer_m_s2[0]" : "xyz[0]"});
    if (!q0 || !a0) {
      note(std::string("imu: not in this log (no ") + (q0 ? "sensor_combined or vehicle_acceleration" : "vehicle_attitude") + ")");
      return;
    }
    // The accelerometer's latest specific force, paired with each attitude.
    std::vector<std::pair<double, Eigen::Vector3d>> forces;
    forces.reserve(topics_.count(accel_topic, 0));
    streams_->imu.reserve(topics_.count("vehicle_attitude", 0));
    const std::size_t step = ulog::sizeOf(a0->primitive);
    topics_.forEach(accel_topic, 0, [&](const ulog::DataMessage& message) {
      ulog::Locator at = *a0;
      Eigen::Vector3d frd;
      for (int i = 0; i < 3; ++i, at.offset += step) frd[i] = value(message, at);
      forces.emplace_back(time(message), Eigen::Vector3d(frd.x(), -frd.y(), -frd.z()));
    });
    LatestSpecificForce latest(std::move(forces));
    const std::size_t q_step = ulog::sizeOf(q0->primitive);
    topics_.forEach("vehicle_attitude", 0, [&](const ulog::DataMessage& message) {
      const double t = time(message);
      const Eigen::Vector3d* force = latest.at(t);
      if (!force) return;
      ulog::Locator at = *q0;
      double q[4];
      for (double& component : q) {
        component = value(message, at);
        at.offset += q_step;
      }
      const Eigen::Quaterniond ned(q[0], q[1], q[2], q[3]);
      if (!(std::abs(ned.norm() - 1.0) < 0.1)) return;
      streams_->imu.push_back({t, swapNedEnuFrdFlu(ned.normalized()), *force});
    });
    note("imu: vehicle_attitude[0].q with " + accel_topic + "[0]." + accel_field);
  }

  void localPosition() {
    const auto z = topics_.field("vehicle_local_position", {"z"});
    const auto vz = topics_.field("vehicle_local_position", {"vz"});
    const auto vx = topics_.field("vehicle_local_position", {"vx"});
    const auto vy = topics_.field("vehicle_local_position", {"vy"});
    const auto vxy_valid = topics_.field("vehicle_local_position", {"v_xy_valid"});
    const auto z_valid = topics_.field("vehicle_local_position", {"z_valid"});
    const auto vz_valid = topics_.field("vehicle_local_position", {"v_z_valid"});
    if (!z || !topics_.has("vehicle_local_position")) {
      note("pose, velocity: not in this log (no vehicle_local_position)");
      return;
    }
    topics_.forEach("vehicle_local_position", 0, [&](const ulog::DataMessage& message) {
      const double t = time(message);
      if (!z_valid || value(message, *z_valid) != 0.0) streams_->altitude_m.push_back({t, -value(message, *z)});
      if (vz && (!vz_valid || value(message, *vz_valid) != 0.0)) {
        streams_->vertical_speed_m_s.push_back({t, -value(message, *vz)});
      }
      if (vx && vy && (!vxy_valid || value(message, *vxy_valid) != 0.0)) {
        // NED: x north, y east.
        streams_->horizontal_velocity.push_back({t, value(message, *vy), value(message, *vx)});
      }
    });
    note(std::string("pose, velocity: vehicle_local_position[0] -z, -vz") + (vx && vy ? ", vy, vx" : ""));
  }

  void airData() {
    const auto pressure = topics_.field("vehicle_air_data", {"baro_pressure_pa"});
    const auto temperature =
        topics_.field("vehicle_air_data", {"baro_temp_celcius", "ambient_temperature", "baro_temp_celsius"});
    if (!pressure || !topics_.has("vehicle_air_data")) {
      note("static_pressure, air_temperature: not in this log (no vehicle_air_data)");
      return;
    }
    topics_.forEach("vehicle_air_data", 0, [&](const ulog::DataMessage& message) {
      streams_->input(input::Scalar::kStaticPressure).push_back({time(message), value(message, *pressure)});
      if (temperature) streams_->input(input::Scalar::kAirTemperature).push_back({time(message), value(message, *temperature)});
    });
    note(std::string("static_pressure: vehicle_air_data[0].baro_pressure_pa; air_temperature: ") +
         (temperature ? "its barometer's temperature" : "not in this log"));
  }

  void rangefinder() {
    const auto distance = topics_.field("distance_sensor", {"current_distance"});
    const auto low = topics_.field("distance_sensor", {"min_distance"});
    const auto high = topics_.field("distance_sensor", {"max_distance"});
    const auto orientation = topics_.field("distance_sensor", {"orientation"});
    if (!distance || !low || !high || !topics_.has("distance_sensor", -1)) {
      note("rangefinder: not in this log (no distance_sensor)");
      return;
    }
    topics_.forEach("distance_sensor", -1, [&](const ulog::DataMessage& message) {
      if (orientation && value(message, *orientation) != kDownward) return;
      const double range = value(message, *distance);
      if (range >= value(message, *low) && range <= value(message, *high)) {
        streams_->input(input::Scalar::kRangefinder).push_back({time(message), range});
      }
    });
    note("rangefinder: distance_sensor.current_distance (downward, within its range)");
  }

  // esc_status' esc_count, when its ESC reports have `field`; else nullopt, and a note says why
  // `signal` is not in this log.
  std::optional<ulog::Locator> escCount(const std::string& signal, const std::string& field) {
    const auto count = topics_.field("esc_status", {"esc_count"});
    if (count && file_.locate("esc_status", "esc[0]." + field)) return count;
    note(signal + ": not in this log (" + (topics_.has("esc_status") ? "esc_status has no " + field : "no esc_status") +
         ")");
    return std::nullopt;
  }

  void motorTemperature() {
    const auto count = escCount("motor_temperature", "motor_temperature");
    if (!count) return;
    std::vector<ulog::Locator> temperatures;
    for (int k = 0;; ++k) {
      const auto at = file_.locate("esc_status", "esc[" + std::to_string(k) + "].motor_temperature");
      if (!at) break;
      temperatures.push_back(*at);
    }
    topics_.forEach("esc_status", 0, [&](const ulog::DataMessage& message) {
      const int escs = std::min<int>(smallInteger(value(message, *count)), static_cast<int>(temperatures.size()));
      double hottest = -std::numeric_limits<double>::infinity();
      for (int k = 0; k < escs; ++k) hottest = std::max(hottest, value(message, temperatures[k]));
      if (escs > 0 && std::isfinite(hottest)) streams_->input(input::Scalar::kMotorTemperature).push_back({time(message), hottest});
    });
    note("motor_temperature: the hottest esc_status[0].esc[k].motor_temperature");
  }

  // ESC k drives motor k, unless the log says which motor (esc_report.actuator_function, PX4 1.14:
  // 101 is Motor1); an ESC not set in esc_online_flags reports nothing.
  void escTelemetry() {
    const auto count = escCount("esc_status", "esc_rpm");
    if (!count) return;
    const auto online = topics_.field("esc_status", {"esc_online_flags"});
    struct Esc {
      ulog::Locator rpm, voltage, current;
      std::optional<ulog::Locator> function;
    };
    std::vector<Esc> escs;
    for (int k = 0; k < kMaxMotors; ++k) {
      const std::string at = "esc[" + std::to_string(k) + "].";
      const auto rpm = file_.locate("esc_status", at + "esc_rpm");
      const auto voltage = file_.locate("esc_status", at + "esc_voltage");
      const auto current = file_.locate("esc_status", at + "esc_current");
      if (!rpm || !voltage || !current) break;
      escs.push_back({*rpm, *voltage, *current, file_.locate("esc_status", at + "actuator_function")});
    }
    constexpr int kMotor1 = 101;
    topics_.forEach("esc_status", 0, [&](const ulog::DataMessage& message) {
      const int n = std::min<int>(smallInteger(value(message, *count)), static_cast<int>(escs.size()));
      const auto flags = online ? static_cast<unsigned>(std::max(0, smallInteger(value(message, *online)))) : ~0u;
      EscTelemetryReading reading;
      reading.time_s = time(message);
      reading.status = true;
      reading.rpm.fill(kNaN);
      reading.current_a.fill(kNaN);
      reading.voltage_v.fill(kNaN);
      reading.count.fill(-1);
      for (int k = 0; k < n; ++k) {
        if (!(flags & (1u << k))) continue;
        const int motor = escs[k].function ? smallInteger(value(message, *escs[k].function)) - kMotor1 : k;
        if (motor < 0 || motor >= kMaxMotors) continue;
        reading.rpm[motor] = value(message, escs[k].rpm);
        reading.voltage_v[motor] = value(message, escs[k].voltage);
        reading.current_a[motor] = value(message, escs[k].current);
        reading.escs = std::max(reading.escs, motor + 1);
      }
      if (reading.escs > 0) streams_->esc.push_back(reading);
    });
    note(std::string("esc_status: esc_status[0].esc[k].esc_rpm, esc_voltage, esc_current (") +
         (escs.empty() || !escs[0].function ? "ESC k on motor k" : "on the motor of its actuator_function") +
         (online ? ", online ESCs only)" : ")"));
  }

 private:
  const ulog::File& file_;
  Topics topics_;
  std::uint64_t first_us_;
  const std::string& path_;
  FlightStreams* streams_;
};

}  // namespace

UlogFlightReader::UlogFlightReader(const std::string& path) : UlogFlightReader(readFlightLogBytes(path), path) {}

UlogFlightReader::UlogFlightReader(std::string bytes, const std::string& path)
    : path_(path), file_(std::make_unique<ulog::File>(std::move(bytes), path)) {
  init();
}

void UlogFlightReader::init() {
  if (file_->data().empty()) {
    throw DataError(nothingReadLine(path_, "no data messages", file_->refusal()));
  }
  std::uint64_t first = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t last = 0;
  for (const ulog::DataMessage& message : file_->data()) {
    const std::uint64_t t = file_->timestampUs(message);
    first = std::min(first, t);
    last = std::max(last, t);
  }
  first_us_ = first;
  duration_s_ = static_cast<double>(last - first) / 1e6;
}

FlightStreams UlogFlightReader::read(const FlightLogOptions& options) const {
  options.validate(path_);
  FlightStreams streams;
  streams.source = path_;
  streams.motors = options.motors;
  SignalReader reader(*file_, first_us_, path_, &streams);
  reader.rcOut(options);
  reader.battery();
  reader.imu();
  reader.localPosition();
  reader.airData();
  reader.rangefinder();
  reader.motorTemperature();
  reader.escTelemetry();
  const std::string unused = options.unusedSourcesNote("a ULog");
  if (!unused.empty()) streams.notes.push_back(unused);
  if (file_->dropouts() > 0) {
    streams.notes.push_back(std::to_string(file_->dropouts()) + " logging dropouts, " +
                            std::to_string(file_->dropoutMs()) + " ms in all");
  }
  return streams;
}

FlightLogFormat ulogFormat() {
  return {"ulog", std::string(ulog::kMagic, 7), [](const std::string& path) -> std::unique_ptr<FlightLogReader> {
            return std::make_unique<UlogFlightReader>(path);
          }};
}

}  // namespace propulsion_estimator
