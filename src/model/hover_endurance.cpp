#include "propulsion_estimator/model/hover_endurance.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace {

constexpr int kBisectionSteps = 60;

double modelled(const PropulsionModel& model, Output output, double value) {
  return model.output(output).source == OutputSource::kNone ? kNaN : value;
}

double thrustAt(const PropulsionModel& model, const Correction& correction, double pwm_us, double voltage_v) {
  OperatingPoint e;
  evaluateCorrected(model, correction, pwm_us, voltage_v, &e);
  return e.thrust_n;
}

// Fixed-point iterations of the current that sags the voltage that sets the current.
constexpr int kSagIterations = 3;
// Below this a loaded voltage counts as at the cut-off (the linear discharge ends exactly there).
constexpr double kCutoffToleranceV = 1e-9;

}  // namespace

double BatteryPack::drawnAt(double voltage_v) const {
  const double drawn = usableAh() * (fullVoltage() - voltage_v) / (fullVoltage() - cutoffVoltage());
  return std::clamp(drawn, 0.0, usableAh());
}

double BatteryPack::drawnAtStateOfCharge(double state_of_charge) const {
  return std::clamp((1.0 - state_of_charge) * capacity_ah, 0.0, usableAh());
}

bool evaluateCorrected(const PropulsionModel& model, const Correction& correction, double pwm_us, double voltage_v,
                       OperatingPoint* point) {
  if (!correction.effects) return model.evaluate(pwm_us, voltage_v, point);
  const effects::Inputs in = effects::correctInputs(*correction.effects, pwm_us, voltage_v, correction.signals);
  const bool accepted = model.evaluate(in.pwm_us, in.voltage_v, point);
  const double factor = std::max(0.0, effects::thrustFactor(*correction.effects, correction.signals, point->thrust_n));
  point->thrust_n *= factor;
  point->efficiency_n_per_w *= factor;
  return accepted;
}

std::optional<HoverPoint> hoverPoint(const PropulsionModel& model, double thrust_n, double voltage_v,
                                     const Correction& correction) {
  const ModelDomain& domain = model.domain();
  // Lowest PWM with enough thrust: a scan for the first crossing, then bisection.
  constexpr int kScan = 200;
  double below = domain.pwm_min_us;
  double above = kNaN;
  for (int k = 0; k <= kScan; ++k) {
    const double x = domain.pwm_min_us + (domain.pwm_max_us - domain.pwm_min_us) * k / kScan;
    if (thrustAt(model, correction, x, voltage_v) >= thrust_n) {
      above = x;
      break;
    }
    below = x;
  }
  if (std::isnan(above)) return std::nullopt;
  // Enough thrust already at the lowest PWM: the hover point lies below the measured range.
  const bool below_pwm_domain = above == domain.pwm_min_us;
  for (int k = 0; k < kBisectionSteps && above > below; ++k) {
    const double middle = 0.5 * (below + above);
    (thrustAt(model, correction, middle, voltage_v) >= thrust_n ? above : below) = middle;
  }
  OperatingPoint e;
  if (!evaluateCorrected(model, correction, above, voltage_v, &e)) return std::nullopt;
  return HoverPoint{voltage_v,
                    above,
                    modelled(model, Output::kCurrent, e.current_a),
                    modelled(model, Output::kPower, e.power_w),
                    modelled(model, Output::kEfficiency, e.efficiency_n_per_w / kNewtonPerGramForce),
                    below_pwm_domain,
                    e.in_domain && !below_pwm_domain};
}

HoverDischarge integrateHoverDischarge(const PropulsionModel& model, double start_voltage_v, double cutoff_voltage_v,
                                       double charge_ah, double thrust_per_motor_n, int motors, int steps) {
  DischargePack pack;
  pack.open_circuit_v = [=](double drawn_ah) {
    return start_voltage_v - (start_voltage_v - cutoff_voltage_v) * drawn_ah / charge_ah;
  };
  pack.charge_ah = charge_ah;
  pack.cutoff_voltage_v = cutoff_voltage_v;
  if (!(start_voltage_v > cutoff_voltage_v)) pack.charge_ah = 0.0;
  return integrateHoverDischarge(model, pack, thrust_per_motor_n, motors, steps);
}

HoverDischarge integrateHoverDischarge(const PropulsionModel& model, const DischargePack& pack,
                                       double thrust_per_motor_n, int motors, int steps, const Correction& correction) {
  HoverDischarge result;
  const ModelDomain& domain = model.domain();
  if (model.output(Output::kCurrent).source == OutputSource::kNone) {
    result.notes.push_back("no endurance: the model has no current");
    return result;
  }
  const double step_ah = pack.charge_ah / steps;
  if (!(step_ah > 0.0) || !(pack.open_circuit_v(0.0) > pack.cutoff_voltage_v)) {
    result.endurance_s = 0.0;
    result.notes.push_back("the pack is at its cut-off");
    return result;
  }
  Correction at_point = correction;
  double hours = 0.0, total_a = 0.0;
  int outside_voltage = 0, below_pwm = 0;
  for (int k = 0; k < steps; ++k) {
    const double open_v = pack.open_circuit_v((k + 0.5) * step_ah);
    double voltage = open_v - pack.resistance_ohm * total_a;
    std::optional<HoverPoint> point;
    for (int iteration = 0; iteration < kSagIterations; ++iteration) {
      at_point.signals.set(effects::Signal::kBatteryCurrent, total_a);
      point = hoverPoint(model, thrust_per_motor_n, voltage, at_point);
      if (!point) break;
      total_a = motors * point->current_a + pack.other_current_a;
      voltage = open_v - pack.resistance_ohm * total_a;
    }
    if (!point) {
      result.notes.push_back("hover ends at " + formatPrintf("%.2f V", voltage) +
                             ": the motors cannot give the hover thrust at that voltage" +
                             (domain.outside == OutsideDomain::kReject ? " (or the model rejects it)" : ""));
      break;
    }
    // The current surface is floored at zero; a zero hover current would be an endless flight.
    if (!(total_a - pack.other_current_a > 0.0)) {
      result.notes.push_back("no endurance: the model's hover current is 0 A at " + formatPrintf("%.2f V", voltage) +
                             " and " + formatPrintf("%.0f us", point->pwm_us) +
                             " (its current surface is at or below zero there)");
      break;
    }
    outside_voltage += voltage < domain.voltage_min_v || voltage > domain.voltage_max_v;
    below_pwm += point->below_pwm_domain;
    // The loaded voltage at the step's ends: the cut-off may lie within it.
    const double start_v = pack.open_circuit_v(k * step_ah) - pack.resistance_ohm * total_a;
    const double end_v = pack.open_circuit_v((k + 1) * step_ah) - pack.resistance_ohm * total_a;
    double share = 1.0;
    if (end_v < pack.cutoff_voltage_v - kCutoffToleranceV) {
      share = start_v > end_v ? std::clamp((start_v - pack.cutoff_voltage_v) / (start_v - end_v), 0.0, 1.0) : 0.0;
    }
    hours += share * step_ah / total_a;
    result.steps.push_back({3600.0 * hours, voltage, total_a, point->pwm_us});
    if (share < 1.0) {
      result.endurance_s = 3600.0 * hours;
      break;
    }
  }
  if (outside_voltage > 0) {
    result.notes.push_back(
        "the battery's " + formatPrintf("%.2f", pack.cutoff_voltage_v) + "-" + formatPrintf("%.2f V", pack.open_circuit_v(0.0)) +
        " leaves the model's " + formatPrintf("%.2f", domain.voltage_min_v) + "-" +
        formatPrintf("%.2f V", domain.voltage_max_v) + " for " + formatPrintf("%.0f%%", 100.0 * outside_voltage / steps) +
        " of the discharge; there the model " +
        (domain.outside == OutsideDomain::kClamp ? "takes the same drive at its nearest voltage" : "extrapolates"));
  }
  if (below_pwm > 0) {
    result.notes.push_back("for " + formatPrintf("%.0f%%", 100.0 * below_pwm / steps) +
                           " of the discharge the hover thrust is below the thrust at the model's lowest PWM (" +
                           formatPrintf("%.0f us", domain.pwm_min_us) + "): the current there is taken at " +
                           formatPrintf("%.0f us", domain.pwm_min_us) + ", so the endurance is likely underestimated");
  }
  if (static_cast<int>(result.steps.size()) == steps) result.endurance_s = 3600.0 * hours;
  return result;
}

}  // namespace propulsion_estimator
