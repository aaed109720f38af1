#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "propulsion_estimator/logs/ulog_writer.h"
#include "propulsion_estimator/sim/flight/flight_sink.h"

namespace propulsion_estimator {
namespace sim {

/// The PX4 message layouts a simulated ULog is written in.
enum class UlogLayout {
  kPx4v1_12,  ///< PX4 1.12: actuator_outputs (PWM us), sensor_combined, battery voltage_filtered_v beside voltage_v
  kPx4v1_14,  ///< newer: actuator_motors (normalised 0..1) only, vehicle_acceleration, other field orders
};

/// Writes a simulated flight as PX4 logs it (docs.px4.io, ULog File Format): actuator outputs,
/// battery_status, vehicle_attitude with the accelerometer's specific force, vehicle_local_position,
/// vehicle_air_data, a downward distance_sensor (and a forward one, instance 0, in the newer layout)
/// and esc_status: the hottest motor's temperature, and each ESC's rotor speed, voltage and current
/// (online in esc_online_flags; in the newer layout in reverse order, each with the motor it drives
/// in actuator_function; else ESC k on motor k) when the flight has ESC telemetry; frames turned to PX4's NED/FRD. Times are
/// `boot_s` + the sample's time, in us. The truth is not written (a ULog has no place for it).
class UlogFlightSink : public FlightSink {
 public:
  /// `pwm_min_us`..`pwm_max_us`: the range normalised outputs are written on (kPx4v1_14).
  UlogFlightSink(UlogLayout layout, double pwm_min_us, double pwm_max_us, double boot_s = 12.5);

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
  std::uint64_t stamp(double time_s) const;
  // One esc_status message: `escs` online (none: a temperature-only message), the first motor at
  // `motor_temperature_c` (NaN: not reported).
  void escStatus(double time_s, const std::vector<EscReading>& escs, double motor_temperature_c);

  UlogLayout layout_;
  double pwm_min_us_;
  double pwm_max_us_;
  double boot_s_;
  ulog::Writer writer_;
  double altitude_m_ = 0.0;
  double air_temperature_c_ = 15.0;
};

}  // namespace sim
}  // namespace propulsion_estimator
