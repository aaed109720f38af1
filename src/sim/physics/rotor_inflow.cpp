#include "propulsion_estimator/sim/physics/rotor_inflow.h"

#include <algorithm>
#include <cmath>

namespace propulsion_estimator {
namespace sim {
namespace {

// Leishman's fit of the measured induced velocity in the vortex ring state, v_i / v_h against
// x = V_c / v_h for -2 <= x <= 0; its constant is kappa.
constexpr double kRing1 = -1.125;
constexpr double kRing2 = -1.372;
constexpr double kRing3 = -1.718;
constexpr double kRing4 = -0.655;

// Induced inflow ratio lambda_i for ideal hover inflow `mu` = sqrt(C_T / 2), axial inflow
// `climb` and ground ratio `ground`. It rises with mu for any climb or descent, which makes the
// thrust equation's root unique.
double inducedInflow(double mu, double climb, double ground) {
  if (mu <= 0.0) return 0.0;
  const double x = climb / mu;
  if (x >= 0.0) return kInducedPowerFactor * ground * mu * (std::sqrt(0.25 * x * x + 1.0) - 0.5 * x);
  if (x >= -2.0) {
    return ground * mu * (kInducedPowerFactor + x * (kRing1 + x * (kRing2 + x * (kRing3 + x * kRing4))));
  }
  return kInducedPowerFactor * ground * mu * (-0.5 * x - std::sqrt(0.25 * x * x - 1.0));
}

// Momentum theory for a disc moving edgewise at e = mu / lambda_h: its induced inflow over the
// hover value, r with r^4 + e^2 r^2 = 1 (1 at rest, about 1 / e when fast).
double edgewiseInducedRatio(double e) {
  const double e2 = e * e;
  return std::sqrt(0.5 * (std::sqrt(e2 * e2 + 4.0) - e2));
}

// Leishman's profile power in forward flight, C_P0 = sigma Cd0 / 8 (1 + 4.65 mu^2).
constexpr double kProfileEdgewiseFactor = 4.65;

}  // namespace

RotorAerodynamics::RotorAerodynamics(const PropellerParams& propeller)
    : radius_m_(propeller.radiusM()),
      k_(0.25 * propeller.solidity * kBladeLiftSlopePerRad),
      hover_thrust_coefficient_(propeller.rotorThrustCoefficient()),
      hover_torque_coefficient_(propeller.rotorTorqueCoefficient()) {
  propeller.validate();
  const double hover_inflow = kInducedPowerFactor * std::sqrt(0.5 * hover_thrust_coefficient_);
  theta_ = hover_thrust_coefficient_ / k_ + hover_inflow;
  profile_torque_coefficient_ = hover_torque_coefficient_ - hover_inflow * hover_thrust_coefficient_;
}

RotorLoad RotorAerodynamics::load(double omega_rad_s, const RotorInflow& inflow) const {
  // Exactly the static coefficients where they were measured, and where the inflow ratio has no
  // meaning (a rotor at rest makes neither thrust nor torque anyway).
  if (inflow.still() || omega_rad_s <= 0.0) return {};
  const double climb = inflow.axial_speed_m_s / (omega_rad_s * radius_m_);
  const double ground = inflow.ground_inflow_ratio;
  const double advance = inflow.edgewise_speed_m_s / (omega_rad_s * radius_m_);
  const double theta = theta_ * (1.0 + 1.5 * advance * advance);
  const double profile_torque = profile_torque_coefficient_ * (1.0 + kProfileEdgewiseFactor * advance * advance);
  // The induced inflow at ideal hover inflow `mu`, edgewise flow included: it still rises with mu
  // (mu r(advance / mu) does), so the root below stays unique.
  const auto induced = [&](double mu) {
    return mu > 0.0 ? inducedInflow(mu, climb, ground) * edgewiseInducedRatio(advance / mu) : 0.0;
  };
  RotorLoad load{0.0, 0.0};
  if (theta - climb > 0.0) {
    // 2 mu^2 = C_T = k (Theta - lambda_c - lambda_i(mu)): the left side rises with mu, the right
    // falls, and at the upper bound the right side (lambda_i >= 0) is no larger than the left.
    double lo = 0.0;
    double hi = std::sqrt(0.5 * k_ * (theta - climb));
    for (int i = 0; i < 100 && hi - lo > 1e-15 * hi; ++i) {
      const double mu = 0.5 * (lo + hi);
      const double residual = 2.0 * mu * mu - k_ * (theta - climb - induced(mu));
      (residual > 0.0 ? hi : lo) = mu;
    }
    const double mu = 0.5 * (lo + hi);
    const double thrust_coefficient = 2.0 * mu * mu;
    const double inflow_ratio = climb + induced(mu);
    load.thrust = thrust_coefficient / hover_thrust_coefficient_;
    load.torque = std::max(0.0, thrust_coefficient * inflow_ratio + profile_torque) / hover_torque_coefficient_;
  } else {
    // The blades meet the air at or beyond zero lift: no thrust, profile torque only.
    load.torque = profile_torque / hover_torque_coefficient_;
  }
  return load;
}

}  // namespace sim
}  // namespace propulsion_estimator
