#pragma once

#include <optional>
#include <string>
#include <vector>

#include "propulsion_estimator/sim/physics/atmosphere.h"
#include "propulsion_estimator/sim/physics/esc.h"
#include "propulsion_estimator/sim/physics/rotor_inflow.h"

namespace propulsion_estimator {
namespace sim {

/// Physical effects that a bench-fitted response surface does not contain. Each is off unless
/// set; any combination may be on. Where each applies:
///   supply_resistance  bench, flight  the ESCs see the sensed voltage minus R times the current
///   air_density        bench, flight  the run's air replaces the bench air of the parameter file
///   ground_effect      flight         the ground lowers the rotors' induced inflow (Cheeseman-Bennett)
///   thrust_loss        flight         airframe blockage and rotor-rotor interaction
///   motor_temperature  bench, flight  winding resistance and magnet flux follow the motor's
///                                     temperature (otherwise they stay at the reference temperature)
///   climb_inflow       flight         the axial inflow of a climb or descent through the rotors
///   esc_offset         flight         the flying ESCs' end points differ from the bench ESC's
///   translational_lift flight         the edgewise flow through the rotors of a vehicle moving
///                                     horizontally (more air through the disc: less induced inflow)
///
/// Three effects take an optional form beside their parameter, so that the law a flight obeys is
/// never exactly the one a diagnosis corrects with (each form's default is the plain law):
///   supply_resistance  current_coefficient_per_a: in flight the path's wire and connectors warm
///                      with the current, R = ohm (1 + c I) with I the ESCs' current of the last
///                      step (the bench and the flight's thrust-reserve check keep ohm)
///   thrust_loss        load_exponent, reference_thrust_n: the airframe's loss follows each
///                      rotor's loading, fraction (T / reference_thrust_n)^load_exponent
///   esc_offset         per_esc_us, gain, dead_band_us: each flying ESC's end points moved by
///                      us + per_esc_us[k], its duty's slope scaled by gain, and its first
///                      dead_band_us above the low end point giving no duty (the duty steps up
///                      at the band's edge: the band matters near idle only)
struct SimEffects {
  std::optional<double> supply_resistance_ohm;  ///< ohm between the battery's terminals and the ESCs
  double supply_current_coefficient_per_a = 0.0;  ///< 1/A; supply_resistance's rise per amp
  double thrust_loss_load_exponent = 0.0;  ///< thrust_loss's dependence on each rotor's loading
  double thrust_loss_reference_thrust_n = 1.0;  ///< N; the rotor thrust at which the loss is `fraction`
  std::vector<double> esc_offset_per_esc_us;  ///< us, per ESC in rotor order, on top of esc_offset_us; empty: none
  double esc_gain = 1.0;  ///< the flying ESCs' duty per us against the bench ESC's
  double esc_dead_band_us = 0.0;  ///< us above the low end point that give no duty
  std::optional<AirConditions> air;  ///< the flight's air, instead of the bench's
  std::optional<double> ground_effect_strength;  ///< 1 = Cheeseman-Bennett's image rotor
  std::optional<double> thrust_loss_fraction;  ///< share of the rotors' thrust the airframe loses, 0..1
  std::optional<double> motor_thermal_resistance_c_per_w;  ///< the motors' cooling during the run
  std::optional<double> climb_inflow_strength;             ///< 1 = the rotor's axial speed, all of it
  std::optional<double> esc_offset_us;  ///< us, both end points of the flying ESCs moved by this
  std::optional<double> translational_lift_strength;  ///< 1 = the rotor's edgewise speed, all of it

  /// Throws FieldError "<effect>.<parameter>" for a value outside its physical range.
  void validate() const;
  /// Throws FieldError "esc_offset.per_esc_us" when esc_offset is on and that list is given with
  /// another count than `escs`, the vehicle's rotors.
  void validateEscCount(int escs) const;
  /// The effects a thrust stand shows (supply_resistance, air_density, motor_temperature); the others
  /// need an airframe, the ground or flight, or (esc_offset) are by definition the bench's reference.
  SimEffects onTheBench() const;
  /// "none", or the effects that are on with their parameters, e.g.
  /// "ground_effect(strength=1) thrust_loss(fraction=0.05)"; for logs and bag metadata.
  std::string summary() const;
};

/// The share of rotor thrust `rotor_thrust_n` (N) the airframe leaves: 1 - thrust_loss's loss at
/// that thrust (its form included; 1 when thrust_loss is off), no lower than 0.
double airframeThrustShare(const SimEffects& effects, double rotor_thrust_n);

/// ESC `esc`'s duty (0..1) at `pulse_us` under esc_offset and its form: `params`' end points moved
/// by esc_offset_us + esc_offset_per_esc_us[esc], the slope scaled by esc_gain, the first
/// esc_dead_band_us above the moved low end point giving none; the bench ESC's duty when
/// esc_offset is off (its form then unused). Throws FieldError "esc_offset.per_esc_us" when
/// esc_offset is on and that list is given without an entry for `esc`.
double escDuty(const SimEffects& effects, const EscParams& params, int esc, double pulse_us);

/// Ground effect after Cheeseman and Bennett (ARC R&M 3021, 1955): the thrust ratio at equal
/// power T_IGE / T_OGE = 1 / (1 - (R / 4z)^2), with its excess over 1 scaled by `strength`; z is
/// taken no lower than R/2, the formula's range of validity. Its inverse is the ratio of the
/// induced inflows at equal thrust (the image rotor's upwash), which is what the rotor model takes.
double groundEffectFactor(double rotor_radius_m, double rotor_height_m, double strength);

/// What the ground_effect, climb_inflow and translational_lift effects make a rotor's disc see, for
/// a rotor of `rotor_radius_m` whose hub is `rotor_height_m` above the ground and moves at
/// `axial_speed_m_s` along its thrust axis (climb positive) and `edgewise_speed_m_s` across it:
/// ground_inflow_ratio = 1 / groundEffectFactor, axial_speed = strength x axial speed and
/// edgewise_speed = strength x edgewise speed (still air where an effect is off). RotorAerodynamics
/// turns it into thrust and torque at the rotor's speed. thrust_loss acts on the airframe, not on
/// the rotor: the flight applies it to the thrust alone.
RotorInflow rotorInflow(const SimEffects& effects, double rotor_radius_m, double rotor_height_m,
                        double axial_speed_m_s, double edgewise_speed_m_s);

}  // namespace sim
}  // namespace propulsion_estimator
