#include "propulsion_estimator/sim/physics/power_train.h"

#include <algorithm>
#include <cmath>

namespace propulsion_estimator {
namespace sim {

PowerTrain::PowerTrain(PropulsionChain chain, int motors, const SimEffects& effects, double initial_temperature_c)
    : PowerTrain(std::vector<PropulsionChain>(motors, chain), effects, initial_temperature_c) {}

PowerTrain::PowerTrain(std::vector<PropulsionChain> chains, const SimEffects& effects, double initial_temperature_c)
    : chains_(std::move(chains)),
      inflow_(chains_.size()),
      effects_(effects),
      path_resistance_ohm_(effects.supply_resistance_ohm.value_or(0.0)),
      temperature_coupled_(effects.motor_thermal_resistance_c_per_w.has_value()),
      thermal_resistance_c_per_w_(effects.motor_thermal_resistance_c_per_w.value_or(
          chains_.front().params().motor.thermal_resistance_c_per_w)),
      omega_rad_s_(chains_.size(), 0.0),
      temperature_c_(chains_.size(), initial_temperature_c),
      inputs_(chains_.size()),
      loads_(chains_.size()) {
  effects.validateEscCount(static_cast<int>(chains_.size()));
  state_.duty.assign(chains_.size(), 0.0);
  state_.motors.assign(chains_.size(), ChainState{});
  state_.winding_temperature_c = temperature_c_;
}

double PowerTrain::electricalTemperatureC(int k) const {
  return temperature_coupled_ ? temperature_c_[k] : chains_[k].params().motor.reference_temperature_c;
}

const PowerTrainState& PowerTrain::step(const std::vector<double>& pwm_us, const Supply& supply,
                                        const AirConditions& air, double dt_s) {
  const int n = motors();
  const double density = air.densityKgM3();
  // The path's resistance at the last step's current: its wire and connectors warm with it.
  const double series_ohm = supply.internal_resistance_ohm +
                            path_resistance_ohm_ * (1.0 + effects_.supply_current_coefficient_per_a * state_.current_a);
  // Input current of ESC k: d (d V - Kt w) / R, so V = source - R_s sum(I) is linear in V.
  double numerator = supply.source_voltage_v;
  double denominator = 1.0;
  for (int k = 0; k < n; ++k) {
    const ChainParams& params = chains_[k].params();
    state_.duty[k] = escDuty(effects_, params.esc, k, pwm_us[k]);
    if (state_.duty[k] <= 0.0) continue;
    const MotorConstants constants = motorConstantsAt(params.motor, electricalTemperatureC(k));
    const double resistance = constants.resistance_ohm + params.esc.resistance_ohm;
    numerator += series_ohm * state_.duty[k] * constants.torque_constant_nm_per_a * omega_rad_s_[k] / resistance;
    denominator += series_ohm * state_.duty[k] * state_.duty[k] / resistance;
  }
  state_.esc_voltage_v = numerator / denominator;
  state_.current_a = 0.0;
  for (int k = 0; k < n; ++k) {
    inputs_[k] = {state_.duty[k], state_.esc_voltage_v, density, electricalTemperatureC(k)};
    loads_[k] = chains_[k].rotor().load(omega_rad_s_[k], inflow_[k]);
    state_.motors[k] = chains_[k].atSpeed(inputs_[k], omega_rad_s_[k], loads_[k]);
    state_.winding_temperature_c[k] = temperature_c_[k];
    state_.current_a += state_.motors[k].input_current_a;
  }
  state_.terminal_voltage_v = supply.source_voltage_v - supply.internal_resistance_ohm * state_.current_a;
  if (dt_s == 0.0) return state_;

  for (int k = 0; k < n; ++k) {
    const PropulsionChain& chain = chains_[k];
    const ChainInput& input = inputs_[k];
    if (state_.duty[k] > 0.0) {
      const double target = chain.steady(input, loads_[k]).omega_rad_s;
      const double time_constant = chain.speedTimeConstantS(input, omega_rad_s_[k], loads_[k]);
      omega_rad_s_[k] = target + (omega_rad_s_[k] - target) * std::exp(-dt_s / time_constant);
    } else {
      omega_rad_s_[k] = std::max(
          0.0, omega_rad_s_[k] - chain.coastingDecelerationRadS2(input, omega_rad_s_[k], loads_[k]) * dt_s);
    }
    temperature_c_[k] = nextWindingTemperature(chain.params().motor, temperature_c_[k], state_.motors[k].heat_w,
                                               air.temperature_c, thermal_resistance_c_per_w_, dt_s);
  }
  return state_;
}

}  // namespace sim
}  // namespace propulsion_estimator
