#include "propulsion_estimator/sim/physics/propulsion_chain.h"

#include <cmath>

#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace sim {

void ChainParams::validate() const {
  esc.validate();
  motor.validate();
  propeller.validate();
}

double ChainState::rpm() const { return omega_rad_s / kRadPerSecPerRpm; }

namespace {

ChainParams validated(ChainParams params) {
  params.validate();
  return params;
}

}  // namespace

PropulsionChain::PropulsionChain(ChainParams params)
    : params_(validated(std::move(params))), rotor_(params_.propeller) {}

double PropulsionChain::torqueFactor(double air_density_kg_m3, const RotorLoad& load) const {
  return params_.propeller.torqueNm(air_density_kg_m3, 1.0 / kTwoPi) * load.torque;
}

ChainState PropulsionChain::atSpeed(const ChainInput& input, double omega_rad_s, const RotorLoad& load) const {
  const MotorConstants motor = motorConstantsAt(params_.motor, input.winding_temperature_c);
  ChainState state;
  state.omega_rad_s = omega_rad_s;
  const double rev_per_s = omega_rad_s / kTwoPi;
  state.thrust_n = params_.propeller.thrustN(input.air_density_kg_m3, rev_per_s) * load.thrust;
  state.torque_nm = params_.propeller.torqueNm(input.air_density_kg_m3, rev_per_s) * load.torque;
  if (input.duty <= 0.0) return state;  // bridge off: no current, no copper loss
  const double resistance = motor.resistance_ohm + params_.esc.resistance_ohm;
  state.motor_current_a =
      (input.duty * input.esc_voltage_v - motor.torque_constant_nm_per_a * omega_rad_s) / resistance;
  state.input_current_a = input.duty * state.motor_current_a;
  state.input_power_w = input.esc_voltage_v * state.input_current_a;
  state.heat_w = state.motor_current_a * state.motor_current_a * motor.resistance_ohm +
                 motor.no_load_current_a * motor.torque_constant_nm_per_a * omega_rad_s;
  return state;
}

ChainState PropulsionChain::steady(const ChainInput& input, const RotorLoad& load) const {
  if (input.duty <= 0.0) return atSpeed(input, 0.0, load);
  const MotorConstants motor = motorConstantsAt(params_.motor, input.winding_temperature_c);
  const double resistance = motor.resistance_ohm + params_.esc.resistance_ohm;
  const double kt = motor.torque_constant_nm_per_a;
  // kQ w^2 + (Kt^2 / R) w - Kt (duty V / R - I0) = 0
  const double b = kt * kt / resistance;
  const double c = kt * (input.duty * input.esc_voltage_v / resistance - motor.no_load_current_a);
  if (c <= 0.0) return atSpeed(input, 0.0, load);
  const double kq = torqueFactor(input.air_density_kg_m3, load);
  // The root in the form that stays accurate when kQ c << b^2.
  const double omega = 2.0 * c / (b + std::sqrt(b * b + 4.0 * kq * c));
  return atSpeed(input, omega, load);
}

double PropulsionChain::speedTimeConstantS(const ChainInput& input, double omega_rad_s,
                                           const RotorLoad& load) const {
  const MotorConstants motor = motorConstantsAt(params_.motor, input.winding_temperature_c);
  const double resistance = motor.resistance_ohm + params_.esc.resistance_ohm;
  const double kt = motor.torque_constant_nm_per_a;
  const double damping = kt * kt / resistance + 2.0 * torqueFactor(input.air_density_kg_m3, load) * omega_rad_s;
  return inertiaKgM2() / damping;
}

double PropulsionChain::coastingDecelerationRadS2(const ChainInput& input, double omega_rad_s,
                                                  const RotorLoad& load) const {
  if (omega_rad_s <= 0.0) return 0.0;
  const MotorConstants motor = motorConstantsAt(params_.motor, input.winding_temperature_c);
  const double drag = torqueFactor(input.air_density_kg_m3, load) * omega_rad_s * omega_rad_s +
                      motor.torque_constant_nm_per_a * motor.no_load_current_a;
  return drag / inertiaKgM2();
}

ChainState PropulsionChain::steadyFromSource(const ChainInput& input, double source_v, double path_ohm, int motors,
                                             double* esc_voltage_v) const {
  ChainInput at = input;
  double lo = 0.0;
  double hi = source_v;
  if (path_ohm > 0.0 && input.duty > 0.0) {
    // V + R n I(V) - source rises with V: bisect to the last bit of the bracket.
    for (int i = 0; i < 200 && hi - lo > 1e-12 * source_v; ++i) {
      at.esc_voltage_v = 0.5 * (lo + hi);
      const double residual = at.esc_voltage_v + path_ohm * motors * steady(at).input_current_a - source_v;
      (residual > 0.0 ? hi : lo) = at.esc_voltage_v;
    }
  }
  at.esc_voltage_v = path_ohm > 0.0 && input.duty > 0.0 ? 0.5 * (lo + hi) : source_v;
  if (esc_voltage_v) *esc_voltage_v = at.esc_voltage_v;
  return steady(at);
}

}  // namespace sim
}  // namespace propulsion_estimator
