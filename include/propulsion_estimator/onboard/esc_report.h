#pragma once

#include <vector>

#include "propulsion_estimator/common/not_a_number.h"

namespace propulsion_estimator {

/// One ESC's report as MAVROS forwards it (mavros_msgs/ESCTelemetryItem from ArduPilot,
/// ESCStatusItem from PX4), in SI units but the rotor speed, which ESCs and MAVROS give in rpm.
struct EscReport {
  double stamp_s = 0.0;  ///< the item's header stamp, s
  double rpm = kNaN;  ///< mechanical rotor speed, rpm
  double current_a = kNaN;  ///< the ESC's input current, A
  double voltage_v = kNaN;  ///< the ESC's input voltage, V
  double temperature_c = kNaN;  ///< deg C; NaN from ESCStatus, which has none
  /// Packets the ESC has sent (ESCTelemetry's count, wraps at 65536); -1 from ESCStatus, which has
  /// none. An unchanged count is the autopilot repeating an ESC's last packet.
  int count = -1;
};

/// One mavros_msgs/ESCTelemetry or ESCStatus message: its stamp and one report per ESC, ESC i
/// driving RCOut channel i + 1 (ArduPilot's servo outputs, PX4's motor outputs).
struct EscTelemetry {
  double stamp_s = 0.0;  ///< the message's header stamp, s
  std::vector<EscReport> escs;  ///< in ESC order
};

}  // namespace propulsion_estimator
