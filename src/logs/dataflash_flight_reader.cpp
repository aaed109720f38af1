#include "propulsion_estimator/logs/dataflash_flight_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/logs/autopilot_frames.h"

namespace propulsion_estimator {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kGoodRange = 4;  // RFND Stat: RangeFinder::Status::Good
constexpr double kDownward = 25;  // RFND Orient: ROTATION_PITCH_270
// s; an ESC's report older than this is not carried into a reading (ArduPilot logs ESC telemetry
// at about 10 Hz per ESC; the live model check's own staleness is esc_telemetry/stale_after_s).
constexpr double kEscFreshS = 0.5;

// ArduPilot's attitude (roll, pitch, yaw in degrees: body FRD to local NED) as the package's
// (body FLU to local ENU, REP-103).
Eigen::Quaterniond enuFromNedEuler(double roll_deg, double pitch_deg, double yaw_deg) {
  const double r = roll_deg * M_PI / 180.0, p = pitch_deg * M_PI / 180.0, y = yaw_deg * M_PI / 180.0;
  const Eigen::Quaterniond ned(Eigen::AngleAxisd(y, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(p, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(r, Eigen::Vector3d::UnitX()));
  return swapNedEnuFrdFlu(ned);
}

// A type's time column in microseconds: TimeUS, or TimeMS in logs before ArduPilot 3.3.
struct TimeColumn {
  dataflash::Column column;
  double to_us = 1.0;
};

std::optional<TimeColumn> timeColumn(const dataflash::File& file, std::uint8_t type) {
  if (const auto us = file.column(type, "TimeUS")) return TimeColumn{*us, 1.0};
  if (const auto ms = file.column(type, "TimeMS")) return TimeColumn{*ms, 1e3};
  return std::nullopt;
}

// Reads one log's signals into FlightStreams on the manifest's clock.
class SignalReader {
 public:
  SignalReader(const dataflash::File& file, double first_us, const std::string& path, FlightStreams* streams)
      : file_(file), first_us_(first_us), path_(path), streams_(streams) {}

  void note(const std::string& line) { streams_->notes.push_back(line); }

  // The messages of type `name`, instance 0 where it has an instance column; with their time in s.
  bool forEach(const std::string& name, const std::function<void(const dataflash::Message&, double)>& use) const {
    const auto type = file_.typeNamed(name);
    if (!type) return false;
    const auto time = timeColumn(file_, *type);
    if (!time) return false;
    std::optional<dataflash::Column> instance;
    for (const char* label : {"Instance", "Inst", "I", "C"}) {
      if ((instance = file_.column(*type, label))) break;
    }
    bool any = false;
    for (const dataflash::Message& message : file_.messages()) {
      if (message.type != *type || (instance && file_.value(message, *instance) != 0.0)) continue;
      use(message, (file_.value(message, time->column) * time->to_us - first_us_) / 1e6);
      any = true;
    }
    return any;
  }
  std::optional<dataflash::Column> column(const std::string& type, const std::string& label) const {
    const auto id = file_.typeNamed(type);
    return id ? file_.column(*id, label) : std::nullopt;
  }
  double value(const dataflash::Message& message, const dataflash::Column& column) const {
    return file_.value(message, column);
  }

  void rcOut(int motors) {
    std::vector<dataflash::Column> channels;
    // Ch1..Ch8 before ArduPilot 3.3, C1..C14 since.
    const std::string prefix = column("RCOU", "C1") || !column("RCOU", "Ch1") ? "C" : "Ch";
    for (int k = 1; k <= motors; ++k) {
      const auto channel = column("RCOU", prefix + std::to_string(k));
      if (!channel) {
        throw DataError(path_ + (file_.typeNamed("RCOU") ? ": rc_out: RCOU has no column C" + std::to_string(k) +
                                                               ", fewer channels than the " + std::to_string(motors) +
                                                               " motors"
                                                         : ": rc_out: no RCOU (a required signal)"));
      }
      channels.push_back(*channel);
    }
    const bool any = forEach("RCOU", [&](const dataflash::Message& message, double t) {
      RcOutFrame& frame = streams_->rc_out.emplace_back();
      frame.time_s = t;
      for (int k = 0; k < motors; ++k) frame.pwm_us[k] = value(message, channels[k]);
    });
    if (!any) throw DataError(path_ + ": rc_out: no RCOU messages (a required signal)");
    note("rc_out: RCOU " + prefix + "1.." + prefix + std::to_string(motors) + " (us)");
  }

  // BAT since ArduPilot 3.3; CURR before, whose integer Volt and Curr are in hundredths.
  void battery() {
    const std::string name = column("BAT", "Volt") || !column("CURR", "Volt") ? "BAT" : "CURR";
    const auto volt = column(name, "Volt");
    const auto curr = column(name, "Curr");
    if (!volt) throw DataError(path_ + ": battery: no BAT with Volt (a required signal)");
    const auto scale = [](const dataflash::Column& c) {
      return std::string("hHiI").find(c.format) != std::string::npos ? 0.01 : 1.0;
    };
    forEach(name, [&](const dataflash::Message& message, double t) {
      streams_->battery.push_back(
          {t, scale(*volt) * value(message, *volt), curr ? scale(*curr) * value(message, *curr) : kNaN});
    });
    if (streams_->battery.empty()) throw DataError(path_ + ": battery: no " + name + " messages (a required signal)");
    note("battery: " + name + " Volt" + (curr ? ", Curr" : ", no current") +
         (scale(*volt) != 1.0 ? " (hundredths)" : ""));
  }

  void imu() {
    const auto roll = column("ATT", "Roll"), pitch = column("ATT", "Pitch"), yaw = column("ATT", "Yaw");
    const auto ax = column("IMU", "AccX"), ay = column("IMU", "AccY"), az = column("IMU", "AccZ");
    if (!roll || !pitch || !yaw || !ax || !ay || !az) {
      note(std::string("imu: not in this log (no ") + (roll ? "IMU" : "ATT") + ")");
      return;
    }
    std::vector<std::pair<double, Eigen::Vector3d>> forces;
    forEach("IMU", [&](const dataflash::Message& message, double t) {
      forces.emplace_back(t, Eigen::Vector3d(value(message, *ax), -value(message, *ay), -value(message, *az)));
    });
    LatestSpecificForce latest(std::move(forces));
    forEach("ATT", [&](const dataflash::Message& message, double t) {
      const Eigen::Vector3d* force = latest.at(t);
      if (!force) return;
      streams_->imu.push_back({t, enuFromNedEuler(value(message, *roll), value(message, *pitch), value(message, *yaw)), *force});
    });
    note("imu: ATT Roll, Pitch, Yaw with IMU AccX..AccZ");
  }

  void localPosition() {
    // XKF1 (EKF3, core 0), NKF1 (EKF2), EKF1 (the first EKF, in logs of ArduPilot 3.2 and 3.3).
    for (const char* ekf : {"XKF1", "NKF1", "EKF1"}) {
      const auto pd = column(ekf, "PD"), vd = column(ekf, "VD");
      const auto vn = column(ekf, "VN"), ve = column(ekf, "VE");
      if (!pd || !vd) continue;
      forEach(ekf, [&](const dataflash::Message& message, double t) {
        streams_->altitude_m.push_back({t, -value(message, *pd)});
        streams_->vertical_speed_m_s.push_back({t, -value(message, *vd)});
        if (vn && ve) {
          streams_->horizontal_velocity.push_back({t, value(message, *ve), value(message, *vn)});
        }
      });
      note(std::string("pose, velocity: ") + ekf + (ekf == std::string("XKF1") ? " (core 0)" : "") + " -PD, -VD" +
           (vn && ve ? ", VE, VN" : ""));
      return;
    }
    const auto alt = column("CTUN", "Alt"), climb = column("CTUN", "CRt");
    if (!alt) {
      note("pose, velocity: not in this log (no XKF1, NKF1, EKF1 or CTUN)");
      return;
    }
    forEach("CTUN", [&](const dataflash::Message& message, double t) {
      streams_->altitude_m.push_back({t, value(message, *alt)});
      if (climb) streams_->vertical_speed_m_s.push_back({t, 0.01 * value(message, *climb)});
    });
    note(std::string("pose, velocity: CTUN Alt") + (climb ? ", CRt (cm/s)" : ", no climb rate"));
  }

  void barometer() {
    const auto press = column("BARO", "Press"), temp = column("BARO", "Temp");
    if (!press) {
      note("static_pressure, air_temperature: not in this log (no BARO)");
      return;
    }
    forEach("BARO", [&](const dataflash::Message& message, double t) {
      streams_->input(input::Scalar::kStaticPressure).push_back({t, value(message, *press)});
      if (temp) streams_->input(input::Scalar::kAirTemperature).push_back({t, value(message, *temp)});
    });
    note(std::string("static_pressure: BARO Press; air_temperature: ") + (temp ? "BARO Temp" : "not in this log"));
  }

  void rangefinder() {
    const auto dist = column("RFND", "Dist"), stat = column("RFND", "Stat"), orient = column("RFND", "Orient");
    if (!dist) {
      note("rangefinder: not in this log (no RFND)");
      return;
    }
    forEach("RFND", [&](const dataflash::Message& message, double t) {
      if (stat && value(message, *stat) != kGoodRange) return;
      if (orient && value(message, *orient) != kDownward) return;
      streams_->input(input::Scalar::kRangefinder).push_back({t, value(message, *dist)});
    });
    note("rangefinder: RFND Dist (good readings)");
  }

  // ESC telemetry: each ESC row (Instance k: RPM, Curr, Volt) updates its motor's latest report;
  // the rows logged at one time make one reading, in which a motor whose last report is older
  // than kEscFreshS is not reported (NaN), as MAVROS' ESCTelemetry carries only what is fresh.
  // Rows without a finite RPM (a motor temperature alone) are no ESC report.
  void escTelemetry(int motors) {
    const auto type = file_.typeNamed("ESC");
    const auto rpm = column("ESC", "RPM");
    const auto instance = column("ESC", "Instance");
    const auto time = type ? timeColumn(file_, *type) : std::nullopt;
    if (!rpm || !instance || !time) {
      note(type ? "esc_telemetry: not in this log (ESC has no RPM or Instance)" : "esc_telemetry: not in this log (no ESC)");
      return;
    }
    const auto current = column("ESC", "Curr");
    const auto voltage = column("ESC", "Volt");
    EscTelemetryReading latest;
    latest.escs = std::min(motors, kMaxMotors);
    latest.rpm.fill(kNaN);
    latest.current_a.fill(kNaN);
    latest.voltage_v.fill(kNaN);
    latest.count.fill(-1);
    std::array<double, kMaxMotors> reported_s;
    reported_s.fill(-std::numeric_limits<double>::infinity());
    double pending_s = kNaN;
    const auto flush = [&]() {
      if (std::isnan(pending_s)) return;
      EscTelemetryReading reading = latest;
      reading.time_s = pending_s;
      for (int k = 0; k < reading.escs; ++k) {
        if (pending_s - reported_s[k] <= kEscFreshS) continue;
        reading.rpm[k] = reading.current_a[k] = reading.voltage_v[k] = kNaN;
      }
      streams_->esc.push_back(reading);
      pending_s = kNaN;
    };
    for (const dataflash::Message& message : file_.messages()) {
      if (message.type != *type) continue;
      const double k = value(message, *instance);
      const double speed = value(message, *rpm);
      if (!(k >= 0 && k < latest.escs) || !std::isfinite(speed)) continue;
      const double t = (value(message, time->column) * time->to_us - first_us_) / 1e6;
      if (t != pending_s) flush();
      const auto i = static_cast<std::size_t>(k);
      latest.rpm[i] = speed;
      latest.current_a[i] = current ? value(message, *current) : kNaN;
      latest.voltage_v[i] = voltage ? value(message, *voltage) : kNaN;
      reported_s[i] = t;
      pending_s = t;
    }
    flush();
    note(streams_->esc.empty() ? "esc_telemetry: not in this log (no ESC row with an RPM)"
                               : "esc_telemetry: ESC RPM, Curr, Volt per Instance (the rows of one time as one reading)");
  }

  void motorTemperature() {
    const auto type = file_.typeNamed("ESC");
    auto temp = column("ESC", "MotTemp");
    if (!temp) temp = column("ESC", "MTemp");
    const auto instance = column("ESC", "Instance");
    const auto time = type ? timeColumn(file_, *type) : std::nullopt;
    if (!temp || !instance || !time) {
      note(type ? "motor_temperature: not in this log (ESC has no MotTemp)" : "motor_temperature: not in this log (no ESC)");
      return;
    }
    // The hottest of the motors' latest readings, at each reading.
    std::vector<double> latest(kMaxMotors, kNaN);
    for (const dataflash::Message& message : file_.messages()) {
      if (message.type != *type) continue;
      const double k = value(message, *instance);
      const double reading_c = value(message, *temp);
      if (!(k >= 0 && k < kMaxMotors) || std::isnan(reading_c)) continue;
      latest[static_cast<std::size_t>(k)] = reading_c;
      double hottest = -std::numeric_limits<double>::infinity();
      for (const double reading : latest) {
        if (!std::isnan(reading)) hottest = std::max(hottest, reading);
      }
      streams_->input(input::Scalar::kMotorTemperature).push_back({(value(message, time->column) * time->to_us - first_us_) / 1e6, hottest});
    }
    note("motor_temperature: the hottest ESC MotTemp");
  }

 private:
  const dataflash::File& file_;
  double first_us_;
  const std::string& path_;
  FlightStreams* streams_;
};

}  // namespace

DataflashFlightReader::DataflashFlightReader(const std::string& path)
    : DataflashFlightReader(readFlightLogBytes(path), path) {}

DataflashFlightReader::DataflashFlightReader(std::string bytes, const std::string& path)
    : path_(path), file_(std::make_unique<dataflash::File>(std::move(bytes), path)) {
  double first = std::numeric_limits<double>::infinity();
  double last = -first;
  std::map<std::uint8_t, std::optional<TimeColumn>> times;
  for (const dataflash::Message& message : file_->messages()) {
    auto time = times.find(message.type);
    if (time == times.end()) time = times.emplace(message.type, timeColumn(*file_, message.type)).first;
    if (!time->second) continue;
    const double t = file_->value(message, time->second->column) * time->second->to_us;
    first = std::min(first, t);
    last = std::max(last, t);
  }
  if (!std::isfinite(first)) {
    throw DataError(nothingReadLine(path_, "no timed messages", file_->refusal()));
  }
  first_us_ = first;
  duration_s_ = (last - first) / 1e6;
}

FlightStreams DataflashFlightReader::read(const FlightLogOptions& options) const {
  options.validate(path_);
  FlightStreams streams;
  streams.source = path_;
  streams.motors = options.motors;
  SignalReader reader(*file_, first_us_, path_, &streams);
  reader.rcOut(options.motors);
  reader.battery();
  reader.imu();
  reader.localPosition();
  reader.barometer();
  reader.rangefinder();
  reader.motorTemperature();
  reader.escTelemetry(options.motors);
  const std::string unused = options.unusedSourcesNote("a DataFlash log");
  if (!unused.empty()) streams.notes.push_back(unused);
  return streams;
}

FlightLogFormat dataflashFormat() {
  return {"dataflash", std::string(dataflash::kMagic, 5),
          [](const std::string& path) -> std::unique_ptr<FlightLogReader> {
            return std::make_unique<DataflashFlightReader>(path);
          }};
}

}  // namespace propulsion_estimator
