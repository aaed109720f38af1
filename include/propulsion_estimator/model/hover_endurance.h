#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "propulsion_estimator/model/model_effects.h"
#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {

/// A LiPo pack for the hover discharge. Its terminal voltage is taken to fall linearly with the
/// charge drawn, from cells x cell_full_v to cells x cell_cutoff_v over usable_fraction x
/// capacity: a plain, stated approximation of a LiPo discharge under a steady load.
struct BatteryPack {
  int cells = 0;  ///< in series
  double capacity_ah = 0.0;  ///< rated capacity, Ah
  double usable_fraction = 0.8;  ///< share of the capacity drawn when the cut-off is reached
  double cell_full_v = 4.2;  ///< V per cell, full
  double cell_cutoff_v = 3.5;  ///< V per cell at the cut-off

  /// V, the full pack
  double fullVoltage() const { return cells * cell_full_v; }
  /// V, the pack at its cut-off
  double cutoffVoltage() const { return cells * cell_cutoff_v; }
  /// Ah drawn from full to the cut-off
  double usableAh() const { return usable_fraction * capacity_ah; }
  /// Charge in Ah drawn when the voltage reads `voltage_v`, clamped to 0..usableAh().
  double drawnAt(double voltage_v) const;
  /// Charge in Ah drawn when `state_of_charge` (0..1, of the capacity) remains, clamped to
  /// 0..usableAh().
  double drawnAtStateOfCharge(double state_of_charge) const;
};

/// One motor's hover operating point at a supply voltage: pulse width in us, current in A and power
/// in W per motor, efficiency in g/W; NaN for an output the model does not have.
struct HoverPoint {
  double voltage_v = 0.0;  ///< V, the supply voltage of the point
  double pwm_us = 0.0;  ///< us
  double current_a = 0.0;  ///< per motor
  double power_w = 0.0;    ///< per motor
  double efficiency_g_per_w = 0.0;  ///< g/W
  /// The hover thrust is below the model's thrust at the lowest PWM of its domain: the hover PWM
  /// lies below the measured range, and pwm_us (with its current and power) is that lowest PWM.
  bool below_pwm_domain = false;
  bool in_domain = false;  ///< false: the voltage was clamped or extrapolated, or below_pwm_domain
};

/// The corrected model a figure is taken with: the model's `effects:` (none: the plain surfaces)
/// and their signals at the moment; its battery current is the total the motors draw at the point
/// (the supply resistance's), which the caller solves for.
struct Correction {
  const effects::ModelEffects* effects = nullptr;  ///< the model's effects; nullptr: the plain surfaces
  effects::Signals signals;  ///< their signals (NaN: that correction skipped)
};

/// One motor at `pwm_us` and battery voltage `voltage_v` through `correction`: the surfaces at the
/// corrected inputs, thrust and efficiency times the effects' thrust factor (floored at zero, as
/// the estimator does). False when the model rejects the point. Throws nothing.
bool evaluateCorrected(const PropulsionModel& model, const Correction& correction, double pwm_us, double voltage_v,
                       OperatingPoint* point);

/// The operating point where one motor gives `thrust_n` at `voltage_v` (evaluate(): the model's
/// outside-domain policy applies; through `correction` when given); nullopt when the model cannot
/// give that much thrust there.
std::optional<HoverPoint> hoverPoint(const PropulsionModel& model, double thrust_n, double voltage_v,
                                     const Correction& correction = {});

/// One step of the hover discharge: hover time in s, battery voltage in V, total current in A and
/// the pulse width in us that holds the hover.
struct DischargeStep {
  double time_s = 0.0;  ///< hover time at the end of the step
  double voltage_v = 0.0;  ///< V at the end of the step
  double total_current_a = 0.0;  ///< A, all motors
  double pwm_us = 0.0;  ///< us at the step's mid voltage
};

/// The hover discharge of a pack from a charge state to its cut-off: the steps, the hover time in
/// s when the cut-off is reached (nullopt when the hover ends before it, or cannot be integrated),
/// and notes on why not or on what the figure rests.
struct HoverDischarge {
  std::vector<DischargeStep> steps;  ///< in time order
  std::optional<double> endurance_s;  ///< s of hover until the cut-off
  std::vector<std::string> notes;  ///< why there is no endurance, or what it rests on
};

/// The pack as the hover discharge sees it: its open-circuit voltage in V after `drawn_ah` has been
/// drawn, the charge in Ah that may be drawn at most, the resistance in ohm between the
/// open-circuit voltage and the terminals (the loaded voltage is open-circuit less resistance x
/// current) and the loaded terminal voltage in V at which the hover ends.
struct DischargePack {
  std::function<double(double drawn_ah)> open_circuit_v;  ///< V after drawn_ah
  double charge_ah = 0.0;         ///< Ah; drawn at most
  double resistance_ohm = 0.0;    ///< ohm; open-circuit to terminals
  double cutoff_voltage_v = 0.0;  ///< V; loaded, where the hover ends
  /// A; what the pack feeds besides the motors (avionics, companion computer, camera): drawn and
  /// sagging the voltage with the motors' current.
  double other_current_a = 0.0;
};

/// Integrates the hover of `motors` motors, each giving `thrust_per_motor_n`, in `steps` equal
/// charge steps until the loaded voltage reaches the pack's cut-off (within the step, linearly) or
/// its charge is drawn: each step's current is the motors' at the hover point of the step's middle,
/// where the loaded voltage and the current are solved together (the current sags the voltage,
/// which raises the current). Needs the model's current (a note says so otherwise). Throws nothing.
HoverDischarge integrateHoverDischarge(const PropulsionModel& model, const DischargePack& pack,
                                       double thrust_per_motor_n, int motors, int steps,
                                       const Correction& correction = {});

/// The same for the linear discharge of compare_models (BatteryPack): `charge_ah` drawn while the
/// voltage falls linearly from `start_voltage_v` to `cutoff_voltage_v`, no resistance, the plain
/// surfaces.
HoverDischarge integrateHoverDischarge(const PropulsionModel& model, double start_voltage_v, double cutoff_voltage_v,
                                       double charge_ah, double thrust_per_motor_n, int motors, int steps);

}  // namespace propulsion_estimator
