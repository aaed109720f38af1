#pragma once

#include <cstdint>
#include <string>

#include "propulsion_estimator/logs/dataflash_writer.h"
#include "propulsion_estimator/sim/flight/flight_sink.h"

namespace propulsion_estimator {
namespace sim {

/// Writes a simulated flight as ArduPilot's DataFlash log: RCOU, BAT, IMU with ATT (NED/FRD,
/// degrees), XKF1, BARO, RFND and ESC (a row per ESC with its RPM, Volt, Curr and Temp; the
/// hottest motor's MotTemp in rows of its own on instance 0), each type's FMT before it. TimeUS is `boot_s` + the sample's time, in us. The truth is not
/// written.
class DataflashFlightSink : public FlightSink {
 public:
  /// A sink whose log starts `boot_s` s after the autopilot booted.
  explicit DataflashFlightSink(double boot_s = 12.5);

  void rcOut(const RcOutSample& sample) override;
  void battery(const BatterySample& sample) override;
  void imu(const ImuSample& sample) override;
  void pose(const PoseSample& sample) override;
  void velocity(const VelocitySample& sample) override;
  void staticPressure(const ScalarSample& sample) override;
  void airTemperature(const ScalarSample& sample) override;
  void rangefinder(const RangeSample& sample) override;
  void motorTemperature(const ScalarSample& sample) override;
  void escTelemetry(const EscTelemetrySample& sample) override;
  void truth(const TruthSample&) override {}

  /// The log so far.
  const std::string& bytes() const { return writer_.bytes(); }
  /// Writes it to `path` (InputError when it cannot be written).
  void save(const std::string& path) const { writer_.save(path); }

 private:
  BinaryPayload start(double time_s) const;

  double boot_s_;
  dataflash::Writer writer_;
  double altitude_m_ = 0.0;
  double air_temperature_c_ = 15.0;
};

}  // namespace sim
}  // namespace propulsion_estimator
