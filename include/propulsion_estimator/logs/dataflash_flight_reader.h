#pragma once

#include <memory>
#include <string>

#include "propulsion_estimator/logs/dataflash_file.h"
#include "propulsion_estimator/logs/flight_log_formats.h"
#include "propulsion_estimator/logs/flight_log_reader.h"

namespace propulsion_estimator {

/// An ArduPilot DataFlash flight read into FlightStreams, columns found by their FMT labels
/// (instance 0 of each, where the message has an instance column):
/// - rc_out: RCOU C1..Cn (PWM us; Ch1..Chn in logs before ArduPilot 3.3);
/// - battery: BAT Volt, Curr; without BAT, CURR Volt, Curr (hundredths where logged as integers);
/// - imu: ATT Roll, Pitch, Yaw (deg, NED/FRD, turned to ENU/FLU) with the latest IMU AccX..AccZ;
/// - pose, velocity: XKF1 (core 0), else NKF1 or EKF1, -PD, -VD; without them CTUN Alt and CRt (cm/s);
/// - static_pressure, air_temperature: BARO Press, Temp;
/// - rangefinder: RFND Dist (m; Stat 4, good, only, and a downward Orient 25 where logged);
/// - motor_temperature: the hottest ESC MotTemp (MTemp; the ESC's own Temp is not a motor's, not read);
/// - esc: ESC RPM, Curr, Volt of Instance 0..n-1 (the ESC telemetry ArduPilot logs), the rows of one
///   time as one reading, a report older than 0.5 s left out.
/// Times: TimeUS (TimeMS in older logs), seconds from the log's first timed message.
class DataflashFlightReader : public FlightLogReader {
 public:
  /// Reads and parses `path`. InputError as requireRegularFile (no such file, a folder, a device); DataError "<path>: not a
  /// DataFlash log ...", "<path>: no timed messages". A file that breaks later is read up to there.
  explicit DataflashFlightReader(const std::string& path);
  /// Parses `bytes` as if read from `path` (fuzzing, tests).
  DataflashFlightReader(std::string bytes, const std::string& path);

  const std::string& path() const override { return path_; }
  double durationS() const override { return duration_s_; }
  /// FlightLogReader::read. DataError "<path>: rc_out: ..." or "<path>: battery: ..." when a
  /// required signal is missing or has fewer channels than motors.
  FlightStreams read(const FlightLogOptions& options) const override;
  std::string refusal() const override { return file_->refusal(); }

  /// The parsed file.
  const dataflash::File& file() const { return *file_; }

 private:
  std::string path_;
  std::unique_ptr<dataflash::File> file_;
  double first_us_ = 0.0;
  double duration_s_ = 0.0;
};

/// The DataFlash format for the FlightLogFormats registry: files that start with dataflash::kMagic.
FlightLogFormat dataflashFormat();

}  // namespace propulsion_estimator
