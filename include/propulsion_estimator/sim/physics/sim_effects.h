#pragma once

#include <optional>
#include <string>

#include "propulsion_estimator/sim/physics/atmosphere.h"

namespace propulsion_estimator {

// Physical effects that a bench-fitted response surface does not contain. Each is off unless
// set; any combination may be on. Where each applies:
//   supply_resistance  bench, flight  the ESCs see the sensed voltage minus R times the current
//   air_density        bench, flight  the run's air replaces the bench air of the parameter file
//   ground_effect      flight         Cheeseman-Bennett thrust gain near the ground
//   thrust_loss        flight         airframe blockage and rotor-rotor interaction
//   motor_temperature  bench, flight  winding resistance and magnet flux follow the motor's
//                                     temperature (otherwise they stay at the reference temperature)
//   climb_inflow       flight         thrust change with vertical speed
//   esc_offset         flight         the flying ESCs' end points differ from the bench ESC's
struct SimEffects {
  std::optional<double> supply_resistance_ohm;
  std::optional<AirConditions> air;
  std::optional<double> ground_effect_strength;  // 1 = Cheeseman-Bennett
  std::optional<double> thrust_loss_fraction;
  std::optional<double> motor_thermal_resistance_c_per_w;  // the motors' cooling during the run
  std::optional<double> climb_inflow_per_m_s;              // thrust fraction lost per m/s of climb
  std::optional<double> esc_offset_us;

  // Throws FieldError "<effect>.<parameter>" for a value outside its physical range.
  void validate() const;
  // The effects a thrust stand shows (supply_resistance, air_density, motor_temperature); the others
  // need an airframe, the ground or flight, or (esc_offset) are by definition the bench's reference.
  SimEffects onTheBench() const;
  // "none", or the effects that are on with their parameters, e.g.
  // "ground_effect(strength=1) thrust_loss(fraction=0.05)"; for logs and bag metadata.
  std::string summary() const;
};

// Factors on an isolated rotor's thrust at fixed rotor speed. The propeller's torque, and so the
// motor's operating point, is left unchanged by all three: at the low advance ratios of hover
// manoeuvres the change of thrust dominates.
struct RotorEffectTerms {
  double ground_effect = 1.0;
  double climb = 1.0;
  double thrust_loss = 1.0;

  double product() const { return ground_effect * climb * thrust_loss; }
};

// Ground effect after Cheeseman and Bennett (ARC R&M 3021, 1955), T_IGE / T_OGE = 1 / (1 - (R / 4z)^2),
// with its excess over 1 scaled by `strength`; z is taken no lower than R/2, the formula's
// range of validity.
double groundEffectFactor(double rotor_radius_m, double rotor_height_m, double strength);

RotorEffectTerms rotorEffectTerms(const SimEffects& effects, double rotor_radius_m, double rotor_height_m,
                                  double climb_rate_m_s);

}  // namespace propulsion_estimator
