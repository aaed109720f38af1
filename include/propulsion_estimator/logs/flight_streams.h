#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "propulsion_estimator/common/input_signal.h"
#include "propulsion_estimator/logs/flight_manifest.h"

namespace propulsion_estimator {

/// The most motors a flight may have (RCOut carries up to 16 channels; multicopters use 4-8).
constexpr int kMaxMotors = 8;

/// One ESC command: the pulse width of each motor, in rotor order.
struct RcOutFrame {
  double time_s = 0.0;  ///< s from the log's first message
  std::array<double, kMaxMotors> pwm_us{};  ///< per motor, us; motors beyond FlightStreams::motors are 0
};

/// One battery report as the autopilot sends it (MAVROS on PX4 negates the current: the sign is
/// left as logged, and the diagnosis takes the discharge direction from the flight as a whole).
struct BatteryReading {
  double time_s = 0.0;  ///< s from the log's first message
  double voltage_v = 0.0;  ///< V at the battery's terminals
  double current_a = 0.0;  ///< NaN when the autopilot has no current sensor
};

/// One IMU message: the attitude (body to local ENU, REP-103) and the specific force the
/// accelerometer measures (gravity included: +9.81 m/s^2 up at rest), in the body frame.
struct ImuReading {
  double time_s = 0.0;  ///< s from the log's first message
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< rotates body into local ENU
  Eigen::Vector3d specific_force_m_s2 = Eigen::Vector3d::Zero();  ///< m/s^2, body frame, gravity included
};

/// The horizontal part of the local velocity (ENU, REP-103).
struct HorizontalVelocityReading {
  double time_s = 0.0;      ///< s from the log's first message
  double east_m_s = 0.0;    ///< m/s
  double north_m_s = 0.0;   ///< m/s
};

/// One ESC telemetry message (mavros_msgs/ESCTelemetry from ArduPilot, ESCStatus from PX4): each
/// ESC's report, ESC i driving RCOut channel i + 1; the first kMaxMotors ESCs are kept, entries
/// past `escs` unused.
struct EscTelemetryReading {
  double time_s = 0.0;  ///< s from the log's first message
  bool status = false;  ///< from PX4's ESCStatus (else ArduPilot's ESCTelemetry)
  int escs = 0;         ///< reports kept, <= kMaxMotors
  std::array<double, kMaxMotors> rpm{};        ///< mechanical rotor speed, rpm; NaN when not reported
  std::array<double, kMaxMotors> current_a{};  ///< the ESC's input current, A; NaN when not reported
  std::array<double, kMaxMotors> voltage_v{};  ///< the ESC's input voltage, V; NaN when not reported
  std::array<int, kMaxMotors> count{};         ///< packets the ESC has sent; -1 when not reported
};

/// A scalar signal in time.
struct ScalarReading {
  double time_s = 0.0;  ///< s from the log's first message
  double value = 0.0;  ///< in the unit the stream's name says
};

/// Everything the diagnosis reads from one flight, as logged, whatever the log's format: times in
/// seconds from the first message of the log (the manifest's clock), values in SI units. Only rc_out and battery are
/// required; an empty stream is a signal the flight does not have.
struct FlightStreams {
  std::string source;  ///< the log it came from, for messages
  int motors = 0;      ///< channels taken from each RcOutFrame
  std::vector<RcOutFrame> rc_out;  ///< required
  std::vector<BatteryReading> battery;  ///< required
  std::vector<ImuReading> imu;  ///< empty without an IMU
  std::vector<ScalarReading> altitude_m;             ///< local position z (up)
  std::vector<ScalarReading> vertical_speed_m_s;     ///< local velocity z (up)
  std::vector<HorizontalVelocityReading> horizontal_velocity;  ///< local velocity x, y (east, north)
  /// Each scalar input's readings, in its ScalarSpec's unit (a rangefinder's valid readings only).
  input::PerScalar<std::vector<ScalarReading>> inputs;
  std::vector<EscTelemetryReading> esc;  ///< ESC telemetry; empty without
  /// How the reader found the signals, one line each ("rc_out: actuator_outputs[0].output[0..3]",
  /// "air_temperature: not in this log"); empty for a reader that says nothing.
  std::vector<std::string> notes;

  /// The readings of the scalar input `scalar`.
  std::vector<ScalarReading>& input(input::Scalar scalar) { return inputs[input::index(scalar)]; }
  /// The readings of the scalar input `scalar`.
  const std::vector<ScalarReading>& input(input::Scalar scalar) const { return inputs[input::index(scalar)]; }
};

/// The signals of a flight, in FlightStreams' order: "rc_out", "battery", "imu", "pose" (altitude_m),
/// "velocity" (vertical_speed_m_s and horizontal_velocity), each scalar input's name (inputs),
/// "esc_telemetry" and "esc_status" (esc: ArduPilot's and PX4's messages). A log format names its
/// sources by these.
const std::vector<std::string>& flightSignalNames();

/// The readings of each signal of `streams`, in flightSignalNames() order.
std::vector<std::size_t> signalCounts(const FlightStreams& streams);

/// A flight of the manifest: its streams and its weighed segments.
struct Flight {
  std::string name;  ///< the log as the manifest names it
  FlightStreams streams;  ///< the flight's signals
  std::vector<ManifestSegment> segments;  ///< the weighed segments, on the streams' clock
  /// "" for a log read to its end; else the reader's one line on where it broke
  /// (FlightLogReader::refusal()): the streams end there.
  std::string damage;
};

}  // namespace propulsion_estimator
