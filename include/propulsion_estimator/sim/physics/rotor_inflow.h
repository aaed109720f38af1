#pragma once

#include "propulsion_estimator/sim/physics/propeller.h"

namespace propulsion_estimator {
namespace sim {

/// @file
/// The propeller as a rotor of blade-element momentum theory (BEMT) with uniform inflow, so that
/// its thrust AND torque at a given rotor speed follow the air flowing through the disc. The
/// static coefficients CT, CQ of the parameter file hold in still air out of ground effect (the
/// bench); a climb, a descent or the ground change the inflow, and with it both.
///
/// References: J. G. Leishman, Principles of Helicopter Aerodynamics, 2nd ed., Cambridge 2006
/// (ch. 2: momentum theory in hover, climb and descent, the induced power factor, the measured
/// induced velocity in the vortex ring state; ch. 3: blade element theory); I. C. Cheeseman and
/// W. E. Bennett, The effect of the ground on a helicopter rotor in forward flight, ARC R&M 3021, 1955.
///
/// Rotorcraft notation: Omega rotor speed, R radius, A = pi R^2; C_T = T / (rho A (Omega R)^2),
/// C_Q = Q / (rho A (Omega R)^2 R) (= C_P); from the propeller's CT, CQ (n in rev/s, D = 2 R)
/// C_T = 4 CT / pi^3 and C_Q = 8 CQ / pi^3. Inflows are velocities over Omega R.
///
/// Blade element theory, linear twist, uniform inflow lambda = lambda_c + lambda_i:
///   C_T = k (Theta - lambda)                k = sigma a / 4, Theta = 2 theta_75 / 3
///   C_Q = lambda C_T + C_Q0                  induced and climb torque, plus profile torque sigma Cd0 / 8
/// with sigma the solidity, a the sections' lift slope, theta_75 the blade angle at 3/4 radius
/// from the zero-lift line, lambda_c = axial speed / (Omega R) (climb > 0). The induced inflow from
/// momentum theory at the rotor's own thrust, lambda_h = sqrt(C_T / 2) (ideal hover) and
/// x = lambda_c / lambda_h:
///   climb              x >= 0       lambda_i = kappa G lambda_h (sqrt(x^2 / 4 + 1) - x / 2)
///   vortex ring state  -2 <= x < 0  lambda_i = G lambda_h (kappa + k1 x + k2 x^2 + k3 x^3 + k4 x^4)
///                                   (Leishman's curve through the measurements: k1 = -1.125,
///                                   k2 = -1.372, k3 = -1.718, k4 = -0.655; momentum theory fails here)
///   windmill brake     x < -2       lambda_i = kappa G lambda_h (-x / 2 - sqrt(x^2 / 4 - 1))
/// kappa = kInducedPowerFactor (propeller.h), G <= 1 the ground's share
/// of the induced inflow at the same thrust (Cheeseman-Bennett's image rotor: G = 1 - (R / 4z)^2).
/// Calibration: in hover out of ground effect (lambda_c = 0, G = 1) the rotor makes exactly CT and
/// CQ, which fixes Theta = C_T0 / k + kappa lambda_h0 and C_Q0 = C_Q - kappa lambda_h0 C_T0.
///
/// What follows, at fixed rotor speed: thrust and torque depend on the effects only through the
/// total inflow lambda, C_T ~ Theta - lambda and C_Q - C_Q0 = k lambda (Theta - lambda).
///   - Ground effect lowers lambda: thrust rises, but by less than Cheeseman-Bennett's factor (an
///     equal-power ratio): with lambda_0 = kappa lambda_h0 and G = 1 - eps, to first order
///     dT / T = lambda_0 / (Theta - lambda_0 / 2) eps (0.68 eps for the thesis' DJI 9443).
///   - A climb raises lambda: dT / T = -(1 - kappa / 2) / (Theta - lambda_0 / 2) lambda_c (-4.8 %
///     per m/s at the thesis quad's hover speed); a slow descent changes it little (the induced
///     inflow rises almost as fast as the rotor descends), a faster one raises the thrust.
///   - The torque changes by k (Theta - 2 lambda) dlambda: the induced torque is largest at
///     lambda = Theta / 2, where the blade's angle of attack at 3/4 radius equals the inflow angle.
///     Rotors at the usual blade loading (C_T / sigma ~ 0.1) hover near it, so at fixed speed their
///     torque hardly moves (DJI 9443: Theta = 0.164, 2 lambda_0 = 0.166; +0.01 % in ground effect at
///     z = 2R, -0.3 % at 1 m/s of climb). The induced torque falls in ground effect at the same
///     THRUST (P_i ~ G): the flight controller, holding the thrust, slows the rotor and draws less
///     current.
/// Edgewise flow (forward flight), mu = edgewise speed / (Omega R), blade element theory with
/// uniform inflow and momentum theory for a disc moving edgewise (Leishman ch. 2.14, 3.3, 5):
///   C_T = k (Theta (1 + 3/2 mu^2) - lambda)   the advancing blade meets faster air
///   lambda_i x r(e),  r^4 + e^2 r^2 = 1, e = mu / lambda_h   the disc meets more air, needs less
///                                                            induced inflow (translational lift)
///   C_Q0 x (1 + 4.65 mu^2)                     the profile torque rises with the edgewise speed
/// The axial part of the flow through a disc tilted into its motion enters as lambda_c. Exact
/// (Glauert) at zero climb out of ground effect; with both, the edgewise ratio r multiplies the
/// axial and ground inflow of above, an approximation of Glauert's coupled
/// lambda_i sqrt(mu^2 + (lambda_c + lambda_i)^2) = C_T / 2.
/// Left out: the blades' drag rising with their angle of attack, the inflow's fore-aft gradient,
/// windmilling (the torque is held at 0 or above, the thrust too).

/// Lift slope a of the blade sections, per radian (2 pi x 0.91, the value Leishman uses for
/// rotor blades; thin cambered sections at propeller Reynolds numbers are near it).
constexpr double kBladeLiftSlopePerRad = 5.73;

/// What a rotor's disc sees besides its own wake.
struct RotorInflow {
  double axial_speed_m_s = 0.0;      ///< the disc's speed along its thrust axis, climb positive
  double ground_inflow_ratio = 1.0;  ///< G: induced inflow in ground effect over that out of it, same thrust
  double edgewise_speed_m_s = 0.0;   ///< the disc's speed across its thrust axis, >= 0

  /// Whether the disc sees still air out of ground effect.
  bool still() const { return axial_speed_m_s == 0.0 && ground_inflow_ratio == 1.0 && edgewise_speed_m_s == 0.0; }
};

/// Factors on the propeller's static thrust and torque (PropellerParams::thrustN, torqueNm) at the
/// same rotor speed.
struct RotorLoad {
  double thrust = 1.0;  ///< factor on the static thrust
  double torque = 1.0;  ///< factor on the static torque
};

/// A propeller as a rotor of blade-element momentum theory (see above): its thrust and torque at a
/// rotor speed in rad/s relative to its static coefficients, for a given inflow.
class RotorAerodynamics {
 public:
  /// Calibrates the blade model on the propeller's static CT and CQ; validates it (FieldError
  /// propeller.*, including a torque coefficient below the induced torque of its thrust).
  explicit RotorAerodynamics(const PropellerParams& propeller);

  /// Thrust and torque factors at `omega_rad_s` in `inflow`; exactly {1, 1} in still air out of
  /// ground effect, and for a rotor at rest.
  RotorLoad load(double omega_rad_s, const RotorInflow& inflow) const;

 private:
  double radius_m_;
  double k_;
  double theta_;
  double hover_thrust_coefficient_;
  double hover_torque_coefficient_;
  double profile_torque_coefficient_;
};

}  // namespace sim
}  // namespace propulsion_estimator
