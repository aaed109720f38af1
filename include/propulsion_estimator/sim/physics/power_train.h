#pragma once

#include <vector>

#include "propulsion_estimator/sim/physics/atmosphere.h"
#include "propulsion_estimator/sim/physics/propulsion_chain.h"
#include "propulsion_estimator/sim/physics/sim_effects.h"

namespace propulsion_estimator {
namespace sim {

/// What the ESCs hang on: an EMF behind a resistance (a battery's open-circuit voltage less its
/// polarisation, behind its series resistance), or a regulated source (no resistance). The
/// voltage sensor of a bench or a power module sits at its terminals.
struct Supply {
  double source_voltage_v = 0.0;  ///< V, the EMF
  double internal_resistance_ohm = 0.0;  ///< ohm, 0 for a regulated source
};

/// The power train at one instant: each ESC's duty cycle (0..1) and motor state, the winding
/// temperatures in deg C, and the voltages (V) and total current (A) on the supply side.
struct PowerTrainState {
  std::vector<double> duty;  ///< one per ESC, 0..1
  std::vector<ChainState> motors;  ///< rotors in their inflow: thrust before airframe effects
  std::vector<double> winding_temperature_c;  ///< deg C, one per motor
  double esc_voltage_v = 0.0;  ///< V at the ESCs' inputs, after any supply_resistance
  double terminal_voltage_v = 0.0;  ///< at the supply's terminals, where the voltage is sensed
  double current_a = 0.0;           ///< drawn from the supply by all ESCs
};

/// Chains on one supply, one per motor, with the rotor speeds' first-order lag and the motors'
/// thermal state. The supply_resistance effect adds a resistance between the supply's terminals
/// and the ESCs, esc_offset moves the ESCs' end points, and motor_temperature makes the electrical
/// constants follow the winding temperature (cooled through the effect's thermal resistance).
/// Each rotor's thrust and torque follow its inflow (setInflow): the motor's operating point,
/// speed and current, answers a climb or the ground as the rotor's torque does.
class PowerTrain {
 public:
  /// `motors` identical chains. Throws FieldError "esc_offset.per_esc_us" when that list is given
  /// with another count than the motors'.
  PowerTrain(PropulsionChain chain, int motors, const SimEffects& effects, double initial_temperature_c);
  /// One chain per motor (a damaged propeller on one of them); throws likewise.
  PowerTrain(std::vector<PropulsionChain> chains, const SimEffects& effects, double initial_temperature_c);

  /// What rotor k's disc sees from the next step on; still air out of ground effect until set.
  void setInflow(int k, const RotorInflow& inflow) { inflow_[k] = inflow; }

  /// Electrical state at the present rotor speeds for these pulse widths (the ESC voltage solved
  /// in closed form: with the speeds given, every ESC's input current is linear in it), with each
  /// rotor's load factors at its present speed and inflow; then the rotor speeds move towards
  /// their steady values and the windings heat or cool over dt_s. Returns the state at the start
  /// of the step; dt_s = 0 only evaluates it.
  const PowerTrainState& step(const std::vector<double>& pwm_us, const Supply& supply, const AirConditions& air,
                              double dt_s);

  /// Chain `k`'s parameters and rotor model.
  const PropulsionChain& chain(int k = 0) const { return chains_[k]; }
  /// Number of motors.
  int motors() const { return static_cast<int>(omega_rad_s_.size()); }
  /// The temperature the electrical constants of motor k are taken at.
  double electricalTemperatureC(int k) const;

 private:
  std::vector<PropulsionChain> chains_;
  std::vector<RotorInflow> inflow_;
  SimEffects effects_;  ///< the ESCs' offset law and the path resistance's current coefficient
  double path_resistance_ohm_;
  bool temperature_coupled_;
  double thermal_resistance_c_per_w_;
  std::vector<double> omega_rad_s_;
  std::vector<double> temperature_c_;
  std::vector<ChainInput> inputs_;  ///< of the present step, sized once
  std::vector<RotorLoad> loads_;
  PowerTrainState state_;
};

}  // namespace sim
}  // namespace propulsion_estimator
