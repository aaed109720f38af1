#pragma once

#include <cmath>

#include "propulsion_estimator/sim/physics/propeller.h"
#include "propulsion_estimator/sim/physics/rotor_inflow.h"

// The rotor model of rotor_inflow.h worked by hand for the tests, after Leishman (2006): C_T =
// k (Theta - lambda), C_Q = lambda C_T + C_Q0, lambda = lambda_c + lambda_i, with lambda_i from
// momentum theory in a climb and the measured curve in a descent (the tests stay above the
// windmill brake state, x < -2), and k, Theta, C_Q0 calibrated so that hover out of ground effect
// gives the propeller's CT and CQ. Solved by damped fixed-point iteration on C_T.
struct HandRotor {
  static constexpr double kPi = 3.14159265358979323846;

  double radius, ct0, cq0, k, lambda0, theta, profile;

  explicit HandRotor(const propulsion_estimator::sim::PropellerParams& propeller)
      : radius(propeller.diameter_m / 2.0),
        ct0(4.0 * propeller.thrust_coefficient / (kPi * kPi * kPi)),
        cq0(8.0 * propeller.torque_coefficient / (kPi * kPi * kPi)),
        k(propeller.solidity * 5.73 / 4.0),
        lambda0(1.15 * std::sqrt(ct0 / 2.0)),
        theta(ct0 / k + lambda0),
        profile(cq0 - lambda0 * ct0) {}

  static double induced(double ct, double climb, double ground) {
    const double vh = std::sqrt(ct / 2.0);
    const double x = climb / vh;
    if (x >= 0.0) return 1.15 * ground * vh * (std::sqrt(x * x / 4.0 + 1.0) - x / 2.0);
    return ground * vh * (1.15 - 1.125 * x - 1.372 * x * x - 1.718 * x * x * x - 0.655 * x * x * x * x);
  }

  // Thrust and torque over their static values at rotor speed omega, axial speed v, ground ratio G.
  propulsion_estimator::sim::RotorLoad load(double omega, double axial_m_s, double ground) const {
    const double climb = axial_m_s / (omega * radius);
    double ct = ct0;
    for (int i = 0; i < 400; ++i) ct = 0.5 * ct + 0.5 * k * (theta - climb - induced(ct, climb, ground));
    const double lambda = climb + induced(ct, climb, ground);
    return {ct / ct0, (ct * lambda + profile) / cq0};
  }

  // The same out of ground effect with no axial speed but an edgewise speed: Glauert's momentum
  // theory for a disc moving edgewise at mu, lambda' sqrt(mu^2 + lambda'^2) = C_T / 2 (lambda' by
  // Newton's method), times the induced power factor; blade element theory with Theta (1 + 3/2
  // mu^2) and profile torque C_Q0 (1 + 4.65 mu^2).
  propulsion_estimator::sim::RotorLoad loadEdgewise(double omega, double edgewise_m_s) const {
    const double mu = edgewise_m_s / (omega * radius);
    const auto glauert = [mu](double ct) {
      double l = std::sqrt(ct / 2.0);
      for (int i = 0; i < 50; ++i) {
        const double root = std::sqrt(mu * mu + l * l);
        l -= (l * root - ct / 2.0) / (root + l * l / root);
      }
      return 1.15 * l;
    };
    double ct = ct0;
    for (int i = 0; i < 400; ++i) ct = 0.5 * ct + 0.5 * k * (theta * (1.0 + 1.5 * mu * mu) - glauert(ct));
    return {ct / ct0, (ct * glauert(ct) + profile * (1.0 + 4.65 * mu * mu)) / cq0};
  }
};

