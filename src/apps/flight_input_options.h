#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/logs/flight_log_reader.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {

// The options that say which vehicle flew a log and where its signals are, shared by the tools
// that read flight logs (diagnose_gap, estimate): --urdf or --frame with --arm-m, --topic,
// --pwm-range-us.
class FlightInputOptions {
 public:
  void addTo(CLI::App& app);
  // The vehicle the options name: the URDF's, the frame's, or (saying so on stdout, prefixed by
  // `tool`) a quadcopter on channels 1-4 at unknown positions. Throws ConfigError naming the option
  // for too many rotors, UsageError for a frame without --arm-m, both a frame and a URDF, or
  // --arm-m alone.
  Vehicle vehicle(const std::string& tool) const;
  // How each log is read for `motors` motors. Throws ConfigError naming the option.
  FlightLogOptions logOptions(int motors) const;
  // The --urdf given, or "".
  const std::string& urdf() const { return urdf_; }
  // The --topic sources as given.
  const std::vector<std::string>& topics() const { return topics_; }

 private:
  std::string urdf_;
  std::string frame_;
  double arm_m_ = kNaN;
  std::vector<std::string> topics_;
  std::vector<double> pwm_range_us_;
};

}  // namespace propulsion_estimator
