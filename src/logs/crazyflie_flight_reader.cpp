#include "propulsion_estimator/logs/crazyflie_flight_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kFullDuty = 65535.0;  // pwm.mK_pwm at full duty

// The Crazyflie's attitude as the package's: body FLU in a world frame z up, yaw about z, then
// pitch about y, then roll about x, right-handed (REP-103's frames: no axis turns). The firmware logs
// stateEstimate.pitch in the legacy CF2 convention, with its sign inverted (state_t's attitude,
// stabilizer_types.h: "legacy CF2 body coordinate system, where pitch is inverted"; its estimators
// log minus the right-handed pitch, nose up positive): the logged pitch is negated here.
Eigen::Quaterniond attitude(double roll_deg, double logged_pitch_deg, double yaw_deg) {
  const double deg = M_PI / 180.0;
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw_deg * deg, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(-logged_pitch_deg * deg, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(roll_deg * deg, Eigen::Vector3d::UnitX()));
}

// Reads one log's signals into FlightStreams on the manifest's clock.
class SignalReader {
 public:
  SignalReader(const crazyflie::File& file, std::uint64_t first_us, const std::string& path, FlightStreams* streams)
      : file_(file), first_us_(first_us), path_(path), streams_(streams) {}

  void rcOut(int motors) {
    const crazyflie::Event* event = file_.eventWith("pwm.m1_pwm");
    if (!event) {
      throw DataError(path_ + (file_.eventWith("motor.m1")
                                   ? ": rc_out: no pwm.m1_pwm (the duty after battery compensation); motor.m1 (the "
                                     "command before it) is not read in its place"
                                   : ": rc_out: no pwm.m1_pwm (a required signal)"));
    }
    std::vector<std::size_t> columns;
    for (int k = 1; k <= motors; ++k) {
      const std::string name = "pwm.m" + std::to_string(k) + "_pwm";
      const auto column = event->column(name);
      if (!column) {
        throw DataError(path_ + ": rc_out: no " + name + " in " + event->name + ": fewer motors logged than the " +
                        std::to_string(motors) + " asked");
      }
      columns.push_back(*column);
    }
    for (std::size_t r = 0; r < event->timestamp_us.size(); ++r) {
      RcOutFrame& frame = streams_->rc_out.emplace_back();
      frame.time_s = seconds(event->timestamp_us[r]);
      for (int k = 0; k < motors; ++k) frame.pwm_us[k] = 1000.0 + 1000.0 * event->columns[columns[k]][r] / kFullDuty;
    }
    if (streams_->rc_out.empty()) throw DataError(path_ + ": rc_out: no " + event->name + " records (a required signal)");
    note("rc_out: pwm.m1_pwm..m" + std::to_string(motors) + "_pwm (duty 0..65535 as 1000..2000 us)");
  }

  void battery() {
    const bool millivolts = file_.eventWith("pm.vbatMV") != nullptr;
    const std::string name = millivolts ? "pm.vbatMV" : "pm.vbat";
    const crazyflie::Event* event = file_.eventWith(name);
    if (!event) throw DataError(path_ + ": battery: no pm.vbatMV or pm.vbat (a required signal)");
    const std::vector<double>& volts = event->columns[*event->column(name)];
    const double scale = millivolts ? 1e-3 : 1.0;
    for (std::size_t r = 0; r < volts.size(); ++r) {
      streams_->battery.push_back({seconds(event->timestamp_us[r]), scale * volts[r], kNaN});
    }
    if (streams_->battery.empty()) throw DataError(path_ + ": battery: no " + event->name + " records (a required signal)");
    note("battery: " + name + (millivolts ? " (mV)" : " (V)") + ", no current (a Crazyflie has no current sensor)");
  }

  // The attitude and the world-frame acceleration of one record make its specific force:
  // stateEstimate.ax..az is the accelerometer's reading turned into the world frame, in g, with the
  // 1 g of gravity taken off z (0 at rest). Roll is required; a pitch or yaw the log lacks is taken
  // as 0, and a note says so (the CrazyPAD motor logs have roll and yaw, some roll alone).
  void imu() {
    const crazyflie::Event* event = file_.eventWith("stateEstimate.roll");
    std::optional<std::size_t> roll, pitch, yaw, ax, ay, az;
    if (event) {
      roll = event->column("stateEstimate.roll");
      pitch = event->column("stateEstimate.pitch");
      yaw = event->column("stateEstimate.yaw");
      ax = event->column("stateEstimate.ax");
      ay = event->column("stateEstimate.ay");
      az = event->column("stateEstimate.az");
    }
    if (!event || !ax || !ay || !az) {
      note("imu: not in this log (no stateEstimate.roll, ax, ay and az in one event)");
      return;
    }
    const auto& c = event->columns;
    for (std::size_t r = 0; r < event->timestamp_us.size(); ++r) {
      const Eigen::Quaterniond q = attitude(c[*roll][r], pitch ? c[*pitch][r] : 0.0, yaw ? c[*yaw][r] : 0.0);
      const Eigen::Vector3d world_g(c[*ax][r], c[*ay][r], c[*az][r] + 1.0);
      streams_->imu.push_back({seconds(event->timestamp_us[r]), q, kStandardGravity * (q.conjugate() * world_g)});
    }
    note(std::string("imu: stateEstimate.roll") + (pitch ? ", pitch (legacy sign turned)" : "") + (yaw ? ", yaw" : "") +
         " (deg) with stateEstimate.ax, ay, az (world frame, g, gravity removed)");
    if (!pitch) note("imu: stateEstimate.pitch not in this log: taken as level");
    if (!yaw) note("imu: stateEstimate.yaw not in this log: heading taken as 0 (the tilt and the world-vertical force do not depend on it)");
  }

  void localPosition() {
    const bool z = scalar("stateEstimate.z", &streams_->altitude_m);
    const bool vz = scalar("stateEstimate.vz", &streams_->vertical_speed_m_s);
    note(z ? "pose: stateEstimate.z" : "pose: not in this log (no stateEstimate.z)");
    const crazyflie::Event* event = file_.eventWith("stateEstimate.vx");
    const auto vx = event ? event->column("stateEstimate.vx") : std::nullopt;
    const auto vy = event ? event->column("stateEstimate.vy") : std::nullopt;
    const bool horizontal = vx && vy;
    if (horizontal) {
      for (std::size_t r = 0; r < event->timestamp_us.size(); ++r) {
        streams_->horizontal_velocity.push_back(
            {seconds(event->timestamp_us[r]), event->columns[*vx][r], event->columns[*vy][r]});
      }
    }
    note(!vz && !horizontal ? std::string("velocity: not in this log (no stateEstimate.vz, vx, vy)")
                            : std::string("velocity: ") + (vz ? "stateEstimate.vz" : "no stateEstimate.vz") + "; " +
                                  (horizontal ? "stateEstimate.vx, vy as east, north (the Crazyflie's world x, y point "
                                                "wherever it started: only the horizontal speed means anything)"
                                              : "no stateEstimate.vx, vy"));
  }

  void note(const std::string& line) { streams_->notes.push_back(line); }

 private:
  double seconds(std::uint64_t timestamp_us) const { return static_cast<double>(timestamp_us - first_us_) / 1e6; }

  // The variable `name` into `stream`; false when the log has no such variable.
  bool scalar(const std::string& name, std::vector<ScalarReading>* stream) const {
    const crazyflie::Event* event = file_.eventWith(name);
    if (!event) return false;
    const std::vector<double>& values = event->columns[*event->column(name)];
    for (std::size_t r = 0; r < values.size(); ++r) stream->push_back({seconds(event->timestamp_us[r]), values[r]});
    return true;
  }

  const crazyflie::File& file_;
  std::uint64_t first_us_;
  const std::string& path_;
  FlightStreams* streams_;
};

}  // namespace

CrazyflieFlightReader::CrazyflieFlightReader(const std::string& path)
    : CrazyflieFlightReader(readFlightLogBytes(path), path) {}

CrazyflieFlightReader::CrazyflieFlightReader(const std::string& bytes, const std::string& path)
    : path_(path), file_(std::make_unique<crazyflie::File>(bytes, path)) {
  std::uint64_t first = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t last = 0;
  for (const crazyflie::Event& event : file_->events()) {
    for (const std::uint64_t t : event.timestamp_us) {
      first = std::min(first, t);
      last = std::max(last, t);
    }
  }
  if (first > last) {
    throw DataError(nothingReadLine(path_, "no records", file_->refusal()));
  }
  first_us_ = first;
  duration_s_ = static_cast<double>(last - first) / 1e6;
}

FlightStreams CrazyflieFlightReader::read(const FlightLogOptions& options) const {
  options.validate(path_);
  FlightStreams streams;
  streams.source = path_;
  streams.motors = options.motors;
  SignalReader reader(*file_, first_us_, path_, &streams);
  reader.rcOut(options.motors);
  reader.battery();
  reader.imu();
  reader.localPosition();
  std::string unread;
  for (input::Scalar scalar : input::kAllScalars) unread += std::string(input::spec(scalar).name) + ", ";
  reader.note(unread + "esc: not read from a Crazyflie uSD log");
  const std::string unused = options.unusedSourcesNote("a Crazyflie uSD log");
  if (!unused.empty()) streams.notes.push_back(unused);
  return streams;
}

FlightLogFormat crazyflieUsdFormat() {
  return {"crazyflie_usd", std::string(crazyflie::kMagic, 3),
          [](const std::string& path) -> std::unique_ptr<FlightLogReader> {
            return std::make_unique<CrazyflieFlightReader>(path);
          }};
}

}  // namespace propulsion_estimator
