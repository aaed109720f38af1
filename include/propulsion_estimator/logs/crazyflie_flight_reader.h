#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "propulsion_estimator/logs/crazyflie_usd_file.h"
#include "propulsion_estimator/logs/flight_log_formats.h"
#include "propulsion_estimator/logs/flight_log_reader.h"

namespace propulsion_estimator {

/// A Crazyflie flight logged by its uSD deck, read into FlightStreams. Variables are found by name
/// in whichever event type carries them (fixedFrequency as a rule):
/// - rc_out: pwm.m1_pwm..pwm.mN_pwm, the duty each brushed motor gets after the firmware's battery
///   compensation (0..65535), as 1000..2000 us; motor.m1.. (the command before it) is not read;
/// - battery: pm.vbatMV (mV), else pm.vbat (V); no current (a Crazyflie has no current sensor);
/// - imu: stateEstimate.roll, pitch, yaw (deg; body FLU in a world frame z up; the logged pitch's
///   legacy sign turned) with stateEstimate.ax, ay, az (world frame, in g, gravity removed) turned
///   into the body's specific force; a pitch or yaw the log lacks is taken as 0, and a note says so;
/// - pose, velocity: stateEstimate.z, vz, and vx, vy as east, north (the Crazyflie's world x, y
///   point wherever it started: only the horizontal speed means anything).
/// Times: seconds from the log's first record.
class CrazyflieFlightReader : public FlightLogReader {
 public:
  /// Reads and parses `path`. InputError as requireRegularFile (no such file, a folder, a device); DataError as crazyflie::File
  /// throws, and "<path>: no records". A file that breaks later is read up to there (refusal()).
  explicit CrazyflieFlightReader(const std::string& path);
  /// Parses `bytes` as if read from `path` (fuzzing, tests).
  CrazyflieFlightReader(const std::string& bytes, const std::string& path);

  const std::string& path() const override { return path_; }
  double durationS() const override { return duration_s_; }
  /// FlightLogReader::read. DataError "<path>: rc_out: ..." when pwm.m1_pwm is missing (naming
  /// motor.m1 when only that is logged) or fewer motors are logged than asked, "<path>: battery: ..."
  /// without pm.vbatMV or pm.vbat.
  FlightStreams read(const FlightLogOptions& options) const override;
  std::string refusal() const override { return file_->refusal(); }

  /// The parsed file.
  const crazyflie::File& file() const { return *file_; }

 private:
  std::string path_;
  std::unique_ptr<crazyflie::File> file_;
  std::uint64_t first_us_ = 0;
  double duration_s_ = 0.0;
};

/// The Crazyflie uSD format for the FlightLogFormats registry: files that start with
/// crazyflie::kMagic (version 2).
FlightLogFormat crazyflieUsdFormat();

}  // namespace propulsion_estimator
