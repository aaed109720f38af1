#pragma once

#include <string>

#include "propulsion_estimator/sim/physics/atmosphere.h"
#include "propulsion_estimator/sim/physics/bench_sensors.h"
#include "propulsion_estimator/sim/physics/lipo_battery.h"
#include "propulsion_estimator/sim/physics/propulsion_chain.h"

namespace propulsion_estimator {
namespace sim {

/// The thrust stand the chain was characterised on.
struct BenchParams {
  AirConditions air;              ///< also the air of flights unless the air_density effect is on
  double sweep_pwm_min_us = 0.0;  ///< the PWM range of this ESC's sweeps (thesis 4.1 and ch. 7)
  double sweep_pwm_max_us = 0.0;  ///< us, see sweep_pwm_min_us
  BenchSensors sensors;  ///< noise and resolution of the bench's sensors

  void validate() const;  ///< FieldError bench.*
};

/// Everything the simulator needs about one propulsion combination: the contents of a
/// config/sim/*.yaml parameter file.
struct SimParams {
  ChainParams chain;  ///< the ESC, motor and propeller
  LipoBatteryParams battery;  ///< the flight battery
  BenchParams bench;  ///< the thrust stand
  std::string source;  ///< file it came from, for messages and metadata

  void validate() const;  ///< FieldError naming the parameter (esc.*, motor.*, propeller.*, battery.*, bench.*)
};

}  // namespace sim
}  // namespace propulsion_estimator
