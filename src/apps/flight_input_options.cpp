#include "flight_input_options.h"

#include <cmath>
#include <cstdio>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/vehicle/vehicle_urdf.h"
#include "tool_command.h"

namespace propulsion_estimator {
namespace {

// Without a URDF: the thesis' quadcopter, its rotors at unknown positions.
constexpr int kDefaultMotors = 4;

std::string signalNames() { return joined(flightSignalNames()); }

}  // namespace

void FlightInputOptions::addTo(CLI::App& app) {
  app.add_option("--urdf", urdf_,
                 "Vehicle URDF: rotors (rotor_<k>_joint, in motor-channel order) and geometry (default: a quadcopter "
                 "on channels 1-4, geometry unknown)");
  app.add_option("--frame", frame_,
                 "Instead of --urdf, a common frame in the autopilots' motor order (PX4's and ArduPilot's agree): quad_x, hexa_x, octo_x (needs --arm-m)")
      ->check(CLI::IsMember(Vehicle::frameNames()));
  app.add_option("--arm-m", arm_m_, "Arm length of --frame: centre to rotor hub, m")
      ->check(numberIn(Vehicle::kMinArmM, Vehicle::kMaxArmM));
  app.add_option("--topic", topics_,
                 "NAME=TOPIC: in a rosbag, read signal NAME from TOPIC instead of MAVROS' (repeatable); names: " +
                     signalNames());
  app.add_option("--pwm-range-us", pwm_range_us_,
                 "MIN MAX: the PWM range a ULog's normalised motor outputs (actuator_motors) map onto, when it "
                 "logs no actuator_outputs (PX4's PWM_MAIN_MIN/MAX)")
      ->expected(2);
}

Vehicle FlightInputOptions::vehicle(const std::string& tool) const {
  if (!frame_.empty()) {
    if (!urdf_.empty()) throw UsageError("--frame: give the frame or --urdf, not both");
    if (std::isnan(arm_m_)) throw UsageError("--frame " + frame_ + ": needs --arm-m, the arm length in m");
    return Vehicle::frame(frame_, arm_m_);
  }
  if (!std::isnan(arm_m_)) throw UsageError("--arm-m: needs --frame");
  if (urdf_.empty()) {
    std::printf("note: no --urdf or --frame: %d motors on RCOut channels 1-%d, thrusting up at unknown positions "
                "(the motor balance needs the geometry; a single weak motor cannot be told from an effect)\n",
                kDefaultMotors, kDefaultMotors);
    return Vehicle::upwardRotors(kDefaultMotors);
  }
  Vehicle vehicle = loadVehicleUrdf(urdf_);
  const int rotors = static_cast<int>(vehicle.rotors.size());
  if (rotors > kMaxMotors) {
    throw ConfigError(urdf_ + ": " + std::to_string(rotors) + " rotors, more than the " + std::to_string(kMaxMotors) +
                      " " + tool + " reads");
  }
  return vehicle;
}

FlightLogOptions FlightInputOptions::logOptions(int motors) const {
  FlightLogOptions options;
  options.motors = motors;
  if (!pwm_range_us_.empty()) {
    options.pwm_min_us = pwm_range_us_[0];
    options.pwm_max_us = pwm_range_us_[1];
    options.validate("--pwm-range-us");
  }
  for (const std::string& argument : topics_) {
    const std::size_t equals = argument.find('=');
    if (equals == std::string::npos || equals + 1 == argument.size()) {
      throw ConfigError("--topic " + argument + ": expected NAME=TOPIC");
    }
    options.sources[argument.substr(0, equals)] = argument.substr(equals + 1);
    options.validate("--topic " + argument);
  }
  return options;
}

}  // namespace propulsion_estimator
