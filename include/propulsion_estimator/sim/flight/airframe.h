#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "propulsion_estimator/sim/flight/vehicle_parts.h"

/// @file
/// The simulated vehicle as the flight physics and the autopilot see it: what a flight profile
/// sets besides its script of segments.
namespace propulsion_estimator {
namespace sim {

/// Autopilots differ in what MAVROS shows of them: PX4 outputs PWM_MAIN_DISARM (900 us) on a
/// disarmed ESC and its battery current arrives negated on /mavros/battery; ArduPilot outputs
/// MOT_PWM_MIN (1000 us), or nothing (0) with MOT_SAFE_DISARM, and a positive current.
enum class AutopilotFlavour { kPx4, kArduPilot };

/// The autopilot's flavour, PWM end points in us and the rate of its /mavros/rc/out in Hz.
struct AutopilotParams {
  AutopilotFlavour flavour = AutopilotFlavour::kPx4;  ///< PX4 or ArduPilot
  double pwm_min_us = 0.0;       ///< mixer output 0 while armed (PX4 PWM_MAIN_MIN, ArduPilot MOT_PWM_MIN/SPIN_ARM)
  double pwm_max_us = 0.0;       ///< mixer output 1
  double disarmed_pwm_us = 0.0;  ///< what the ESCs get while disarmed
  double rc_out_rate_hz = 0.0;   ///< /mavros/rc/out (and /sim/truth) publication rate
};

/// What a profile sets of the vehicle besides its URDF's content: centre-of-mass offset, landing
/// gear, drag area, the battery's initial state of charge and its own parts (SI units).
struct VehicleSetup {
  std::string urdf_path;                                              ///< resolved against the profile's folder
  Eigen::Vector3d centre_of_mass_offset_m = Eigen::Vector3d::Zero();  ///< added to the URDF's centre of mass
  double landing_gear_height_m = 0.0;                                 ///< base_link above the ground when landed
  double landing_gear_half_width_m = 0.0;                             ///< feet at (+-w, +-w) under base_link
  double drag_area_m2 = 0.0;                                          ///< Cd A of the airframe
  double battery_initial_soc = 1.0;  ///< 0..1, at the start of the flight
  /// Flight controller, companion computer, radios and camera: drawn from the battery beside the
  /// ESCs and seen by the current sensor, never by the ESCs (0 A unless the profile says).
  double avionics_current_a = 0.0;
  /// Each motor's own parts, drawn from the vehicle's seed (vehicle_parts.h); none: every motor
  /// flies the parameter file's chain.
  std::optional<VehicleParts> parts;
};

/// A payload hangs on a cable from a point of the airframe; it is attached and changed while landed.
struct PayloadCable {
  double length_m = 0.0;  ///< m, unstretched
  Eigen::Vector3d attach_point_m = Eigen::Vector3d::Zero();  ///< in base_link
  double stiffness_n_per_m = 0.0;                            ///< along the cable, which only pulls
  double damping_n_s_per_m = 0.0;  ///< along the cable
};

/// How a damaged propeller loses its thrust.
enum class PropellerDamage {
  /// Chipped or cut down (or the wrong size): flown as a geometrically similar smaller propeller
  /// (scaledPropeller), so it absorbs less torque too, and the yaw balance moves.
  kChipped,
  /// A worn or bent blade: the thrust coefficient falls, the torque coefficient (the blades'
  /// profile drag) stays (wornPropeller): at the same thrust it spins faster and absorbs more.
  kWorn,
};

/// A propeller that makes less thrust than the others at the same speed.
struct PropellerFault {
  int motor = 0;               ///< 1-based, in the vehicle's rotor order (its RC channel)
  double thrust_factor = 1.0;  ///< of the intact propeller's thrust at the same rotor speed
  PropellerDamage damage = PropellerDamage::kChipped;  ///< how it lost it
};

/// Faults of the vehicle that the library of effects does not hold, for validating the gap
/// diagnosis (a centre of gravity off the centre is VehicleSetup::centre_of_mass_offset_m).
struct VehicleFaults {
  std::optional<PropellerFault> weak_propeller;  ///< a propeller weaker than the others; none when absent
};

}  // namespace sim
}  // namespace propulsion_estimator
