#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "propulsion_estimator/common/input_signal.h"
#include "propulsion_estimator/estimation/hover_detector.h"
#include "propulsion_estimator/estimation/payload_estimator.h"

namespace propulsion_estimator {

/// Everything the estimator needs besides the model and the vehicle. Read from rosparam by the
/// node (ros/estimator_params.h); defaults are the documented ones (docs/node.md, "Parameters").
struct EstimatorConfig {
  std::vector<int> motor_channels{1, 2, 3, 4};  ///< RCOut channels of the motors, 1-based, in rotor order
  /// PWM at or below this means a disarmed or stopped motor (PX4 sends 900, ArduPilot 1000 or 0;
  /// raise it to 1000 for ArduPilot).
  double disarmed_pwm_max_us = 950.0;
  double battery_timeout_s = 5.0;  ///< MAVROS on PX4 may publish the battery at 0.5-1 Hz
  double imu_timeout_s = 0.5;  ///< s; an older attitude is not used for tilt or acceleration compensation
  double velocity_timeout_s = 0.5;  ///< s; an older vertical speed is not used by the hover check
  /// How long a reading of each scalar input stays in use, by input::index (`<name>/timeout_s`;
  /// defaults in the inputs' entries, a few periods of what MAVROS publishes); older, the
  /// correction that reads it is skipped. The battery current ages with the voltage
  /// (battery_timeout_s), the vertical speed with the velocity (velocity_timeout_s).
  input::PerScalar<double> input_timeout_s = input::defaultTimeouts();
  bool compensate_tilt = true;          ///< vertical thrust = sum T_i (R a_i) . z, with the IMU's attitude
  bool compensate_acceleration = true;  ///< mass = vertical thrust / (g + vertical acceleration)
  double accel_filter_s = 0.3;          ///< low-pass of the vertical acceleration
  double accel_bias_filter_s = 30.0;    ///< average taken as accelerometer bias
  double clock_jump_reset_s = 1.0;      ///< the clock going back this far (a bag restarted) resets all
  /// RCOut stamped further ahead of its receipt is refused (clocks out of sync, a corrupt stamp); a
  /// replayed bag's simulated clock may lag the stamps by a few of its ticks.
  double max_stamp_ahead_s = 0.5;
  std::optional<double> empty_mass_kg;  ///< configured empty mass; a tare overrides it
  HoverConfig hover;  ///< when the vehicle hovers
  PayloadConfig payload;  ///< how the hover mass is averaged

  /// ConfigError naming the parameter and its value. `rotors`: how many rotors the vehicle has.
  /// The windows are sized by time, in fixed memory (BinnedWindow), so no rate bounds them.
  void validate(std::size_t rotors) const;
  /// The timeout of `scalar`, s.
  double inputTimeoutS(input::Scalar scalar) const { return input_timeout_s[input::index(scalar)]; }
};

}  // namespace propulsion_estimator
