#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "propulsion_estimator/logs/flight_log_formats.h"
#include "propulsion_estimator/logs/flight_log_reader.h"
#include "propulsion_estimator/logs/ulog_file.h"

namespace propulsion_estimator {

/// A PX4 ULog flight read into FlightStreams. Fields are found by name in the log's own formats,
/// so PX4 1.12 and earlier and newer layouts read alike. Topics, instance 0 unless said:
/// - rc_out: actuator_outputs.output[k] (PWM us); without it actuator_motors.control[k] (0..1,
///   NaN stopped) mapped through the options' PWM range, which is then required;
/// - battery: battery_status.voltage_v (voltage_filtered_v in old logs), current_a (-1 unknown: NaN);
/// - imu: vehicle_attitude.q (NED/FRD, turned to ENU/FLU) with the latest specific force of
///   sensor_combined.accelerometer_m_s2, or vehicle_acceleration.xyz (FRD, turned to FLU);
/// - pose, velocity: vehicle_local_position -z, -vz (skipped while z_valid / v_z_valid is false);
/// - static_pressure, air_temperature: vehicle_air_data.baro_pressure_pa, baro_temp_celcius
///   (ambient_temperature in newer logs);
/// - rangefinder: distance_sensor.current_distance of a downward sensor (orientation 25), within
///   min_distance..max_distance, any instance;
/// - motor_temperature: the hottest esc_status.esc[k].motor_temperature (PX4's ESC telemetry; the
///   ESCs' own esc_temperature is not a motor's and is not read).
/// Times: seconds from the log's first data message (the manifest's clock).
class UlogFlightReader : public FlightLogReader {
 public:
  /// Reads and parses `path`. InputError as requireRegularFile (no such file, a folder, a device); DataError "<path>: not a ULog
  /// ...", "<path>: no data messages". A file that breaks later is read up to there (refusal()).
  explicit UlogFlightReader(const std::string& path);
  /// Parses `bytes` as if read from `path` (fuzzing, tests).
  UlogFlightReader(std::string bytes, const std::string& path);

  const std::string& path() const override { return path_; }
  double durationS() const override { return duration_s_; }
  /// FlightLogReader::read. DataError "<path>: rc_out: ..." or "<path>: battery: ..." when a
  /// required signal is missing or has fewer outputs than motors; ConfigError "<path>: rc_out: only
  /// actuator_motors (normalised) is logged: give the PWM range" when it is needed and not given.
  FlightStreams read(const FlightLogOptions& options) const override;
  std::string refusal() const override { return file_->refusal(); }

  /// The parsed file.
  const ulog::File& file() const { return *file_; }

 private:
  void init();

  std::string path_;
  std::unique_ptr<ulog::File> file_;
  std::uint64_t first_us_ = 0;
  double duration_s_ = 0.0;
};

/// The ULog format for the FlightLogFormats registry: files that start with ulog::kMagic.
FlightLogFormat ulogFormat();

}  // namespace propulsion_estimator
