#pragma once

#include "propulsion_estimator/sim/physics/bldc_motor.h"
#include "propulsion_estimator/sim/physics/esc.h"
#include "propulsion_estimator/sim/physics/propeller.h"
#include "propulsion_estimator/sim/physics/rotor_inflow.h"

namespace propulsion_estimator {
namespace sim {

/// One ESC-motor-propeller combination.
struct ChainParams {
  EscParams esc;  ///< the ESC
  BldcMotorParams motor;  ///< the motor
  PropellerParams propeller;  ///< the propeller

  void validate() const;  ///< FieldError esc.* / motor.* / propeller.*
};

/// What the chain runs at: ESC duty, ESC input voltage, air, and the winding temperature the
/// motor's electrical constants are taken at.
struct ChainInput {
  double duty = 0.0;  ///< 0..1
  double esc_voltage_v = 0.0;  ///< V at the ESC's input
  double air_density_kg_m3 = 0.0;  ///< kg/m^3
  double winding_temperature_c = 0.0;  ///< deg C, the motor's electrical constants are taken at it
};

/// State of one chain. Thrust is the rotor's in its inflow (the `load` it was evaluated with),
/// without airframe effects.
struct ChainState {
  double omega_rad_s = 0.0;  ///< rotor speed, rad/s
  double thrust_n = 0.0;  ///< N, along the rotor axis
  double torque_nm = 0.0;  ///< propeller's aerodynamic torque
  double motor_current_a = 0.0;  ///< A, in the winding
  double input_current_a = 0.0;  ///< drawn by the ESC from its supply
  double input_power_w = 0.0;    ///< ESC input voltage * input current
  double heat_w = 0.0;           ///< dissipated in the motor (winding copper + no-load losses)

  double rpm() const;  ///< rotor speed, rpm
};

/// One ESC, motor and propeller (ChainParams): the operating point at a rotor speed, the steady
/// one, and the speed's dynamics. The constructor validates the parameters (FieldError).
///
/// `load` in the functions below: the factors the rotor's inflow puts on the propeller's static
/// thrust and torque (RotorAerodynamics::load); the default is still air out of ground effect.
class PropulsionChain {
 public:
  explicit PropulsionChain(ChainParams params);  ///< validates

  /// Steady operating point: the motor torque Kt (I - I0) balances the propeller's torque, with
  /// I = (duty V - Kt w) / R and R the winding plus the ESC's resistance; a quadratic in w,
  /// solved in closed form with the load factors held (they depend on w only through the inflow;
  /// the power train re-evaluates them every step). Below the voltage that overcomes the no-load
  /// current the rotor stands.
  ChainState steady(const ChainInput& input, const RotorLoad& load = {}) const;

  /// Electrical state at a given rotor speed (during a speed change the motor current is set by
  /// the voltage balance alone, its electrical time constant being microseconds).
  ChainState atSpeed(const ChainInput& input, double omega_rad_s, const RotorLoad& load = {}) const;

  /// Time constant of the rotor speed's first-order response at `omega_rad_s`: rotor and propeller
  /// inertia over the derivative of the net torque, J / (Kt^2 / R + 2 kQ w).
  double speedTimeConstantS(const ChainInput& input, double omega_rad_s, const RotorLoad& load = {}) const;

  /// Steady operating point of `motors` identical chains at the same duty fed from a source of EMF
  /// `source_v` through `path_ohm`: the ESC voltage solves V = source_v - path_ohm * motors * I(V)
  /// (bisection; I(V) rises with V, so the root is unique). `esc_voltage_v` receives V.
  ChainState steadyFromSource(const ChainInput& input, double source_v, double path_ohm, int motors,
                              double* esc_voltage_v) const;

  /// Deceleration of a rotor whose ESC is off: propeller drag and no-load friction only.
  double coastingDecelerationRadS2(const ChainInput& input, double omega_rad_s, const RotorLoad& load = {}) const;

  /// As validated.
  const ChainParams& params() const { return params_; }
  /// The rotor's inflow model.
  const RotorAerodynamics& rotor() const { return rotor_; }
  /// kg m^2, motor rotor and propeller.
  double inertiaKgM2() const { return params_.motor.rotor_inertia_kg_m2 + params_.propeller.inertia_kg_m2; }

 private:
  /// kQ of Q = kQ w^2, with the load's torque factor.
  double torqueFactor(double air_density_kg_m3, const RotorLoad& load) const;

  ChainParams params_;
  RotorAerodynamics rotor_;
};

}  // namespace sim
}  // namespace propulsion_estimator
