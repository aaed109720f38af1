#include "propulsion_estimator/fitting/model_comparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "propulsion_estimator/fitting/bench_dataset.h"
#include "propulsion_estimator/common/cells_in_series.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace fitting {
namespace {

double modelled(const PropulsionModel& model, Output output, double value) {
  return model.output(output).source == OutputSource::kNone ? kNaN : value;
}

// The model's estimate in chapter 7 units; nullopt when the model rejects the point.
std::optional<ComparisonSample> sample(const PropulsionModel& model, double pwm_us, double voltage_v) {
  OperatingPoint e;
  if (!model.evaluate(pwm_us, voltage_v, &e)) return std::nullopt;
  ComparisonSample s;
  s.pwm_us = pwm_us;
  s.voltage_v = voltage_v;
  s.thrust_g = e.thrust_n / kNewtonPerGramForce;
  s.current_a = modelled(model, Output::kCurrent, e.current_a);
  s.power_w = modelled(model, Output::kPower, e.power_w);
  s.efficiency_g_per_w = modelled(model, Output::kEfficiency, e.efficiency_n_per_w / kNewtonPerGramForce);
  s.rpm = modelled(model, Output::kRpm, e.rpm);
  return s;
}

void integrateHover(const PropulsionModel& model, const HoverOptions& hover, ModelComparison* result) {
  const BatteryPack pack = hover.pack();
  HoverDischarge discharge = integrateHoverDischarge(model, pack.fullVoltage(), pack.cutoffVoltage(), pack.usableAh(),
                                                     hover.thrustPerMotorN(), hover.motors, hover.steps);
  result->discharge = std::move(discharge.steps);
  result->hover_notes.insert(result->hover_notes.end(), discharge.notes.begin(), discharge.notes.end());
  if (discharge.endurance_s) result->endurance_min = *discharge.endurance_s / 60.0;
}

}  // namespace

double HoverOptions::thrustPerMotorN() const { return vehicle_mass_kg * kStandardGravity / motors; }

BatteryPack HoverOptions::pack() const {
  return BatteryPack{cells, capacity_mah / 1000.0, usable_fraction, cell_full_v, cell_cutoff_v};
}

void HoverOptions::validate() const {
  if (!(vehicle_mass_kg > 0.0)) throw ConfigError("--mass-kg must be positive");
  if (motors < 1) throw ConfigError("--motors must be at least 1");
  if (const std::string problem = cellsInSeriesProblem(cells); !problem.empty()) throw ConfigError("--cells " + problem);
  if (!(capacity_mah > 0.0)) throw ConfigError("--capacity-mah must be positive");
  if (!(usable_fraction > 0.0 && usable_fraction <= 1.0)) throw ConfigError("--usable-fraction must be in (0, 1]");
  if (!(cell_cutoff_v > 0.0 && cell_cutoff_v < cell_full_v)) {
    throw ConfigError("--cell-cutoff-v must be positive and below --cell-full-v");
  }
  if (steps < 1) throw ConfigError("integration steps must be at least 1");
}

void ComparisonOptions::validate() const {
  if (voltage_v && !(*voltage_v > 0.0)) throw ConfigError("--voltage must be positive");
  if (curve_points < 2) throw ConfigError("curve points must be at least 2");
  if (hover) hover->validate();
}

ModelComparison compareModel(const std::string& label, const PropulsionModel& model, const std::vector<BenchLog>& logs,
                             const ComparisonOptions& options) {
  options.validate();
  const ModelDomain& domain = model.domain();
  ModelComparison result;
  result.label = label;
  result.metadata = model.metadata();
  result.voltage_v = options.voltage_v.value_or(domain.voltage_max_v);
  if (result.voltage_v < domain.voltage_min_v || result.voltage_v > domain.voltage_max_v) {
    const std::string outside = "--voltage " + formatPrintf("%.2f V", result.voltage_v) + " is outside the model's " +
                                formatPrintf("%.2f", domain.voltage_min_v) + "-" +
                                formatPrintf("%.2f V", domain.voltage_max_v) + " domain";
    switch (domain.outside) {
      case OutsideDomain::kReject:
        throw ConfigError(label + ": " + outside + " and the model rejects it (policy reject): choose --voltage "
                          "inside it");
      case OutsideDomain::kClamp:
        // Evaluating would clamp anyway; the row then says at which voltage its values are.
        result.voltage_v = std::clamp(result.voltage_v, domain.voltage_min_v, domain.voltage_max_v);
        result.notes.push_back(outside + ": its row is the model at " + formatPrintf("%.2f V", result.voltage_v) +
                               ", where the model clamps the voltage");
        break;
      case OutsideDomain::kExtrapolate:
        result.notes.push_back(outside + ": its row extrapolates the surfaces (policy extrapolate)");
        break;
    }
  }
  for (int k = 0; k < options.curve_points; ++k) {
    const double x = domain.pwm_min_us + (domain.pwm_max_us - domain.pwm_min_us) * k / (options.curve_points - 1);
    const std::optional<ComparisonSample> s = sample(model, x, result.voltage_v);
    if (!s) throw ConfigError(label + ": the model rejects " + formatPrintf("%.0f us", x));
    result.curve.push_back(*s);
  }
  result.max_current_a = result.max_power_w = result.max_rpm = -std::numeric_limits<double>::infinity();
  for (const ComparisonSample& s : result.curve) {
    result.max_thrust_g = std::max(result.max_thrust_g, s.thrust_g);
    result.max_current_a = std::max(result.max_current_a, s.current_a);
    result.max_rpm = std::max(result.max_rpm, s.rpm);
    if (s.power_w > result.max_power_w) {
      result.max_power_w = s.power_w;
      result.efficiency_at_max_power_g_per_w = s.efficiency_g_per_w;
    }
  }
  for (double* value : {&result.max_current_a, &result.max_power_w, &result.max_rpm}) {
    if (std::isinf(*value)) *value = kNaN;
  }
  if (std::isnan(result.max_power_w)) result.efficiency_at_max_power_g_per_w = kNaN;
  result.peak_efficiency_g_per_w = result.peak_efficiency_pwm_us = kNaN;
  for (const ComparisonSample& s : result.curve) {
    if (!(s.power_w >= kEfficiencyMinPowerShare * result.max_power_w)) continue;
    if (std::isnan(result.peak_efficiency_g_per_w) || s.efficiency_g_per_w > result.peak_efficiency_g_per_w) {
      result.peak_efficiency_g_per_w = s.efficiency_g_per_w;
      result.peak_efficiency_pwm_us = s.pwm_us;
    }
  }

  if (!logs.empty()) {
    for (const BenchLog& log : logs) {
      if (!log.has(BenchColumn::kMotorTemp)) continue;
      const std::vector<double>& t = log.column(BenchColumn::kMotorTemp);
      const double hottest = *std::max_element(t.begin(), t.end());
      result.max_motor_temp_c = std::max(result.max_motor_temp_c.value_or(hottest), hottest);
    }
    const BenchDataset data = buildBenchDataset(logs, LevelOptions{});
    for (std::size_t row = 0; row < data.rows(); ++row) {
      if (std::abs(data.voltage_v[row] - result.voltage_v) > kNearVoltageV) continue;
      result.logged_near.push_back({data.pwm_us[row], data.voltage_v[row], data.output(Output::kThrust)[row],
                                    data.output(Output::kCurrent)[row], data.output(Output::kPower)[row],
                                    data.output(Output::kEfficiency)[row], data.output(Output::kRpm)[row]});
    }
  }

  if (options.hover) {
    result.hover = hoverPoint(model, options.hover->thrustPerMotorN(), options.hover->midVoltage());
    if (!result.hover) {
      result.hover_notes.push_back("cannot hover: the motors give less than the hover thrust at " +
                                   formatPrintf("%.2f V", options.hover->midVoltage()));
    } else {
      const double voltage = options.hover->midVoltage();
      if (voltage < domain.voltage_min_v || voltage > domain.voltage_max_v) {
        result.hover_notes.push_back("the hover point's " + formatPrintf("%.2f V", voltage) +
                                     " is outside the model's domain");
      }
      if (result.hover->below_pwm_domain) {
        OperatingPoint lowest;
        model.evaluate(domain.pwm_min_us, voltage, &lowest);
        result.hover_notes.push_back(
            "the hover thrust (" + formatPrintf("%.1f g", options.hover->thrustPerMotorN() / kNewtonPerGramForce) +
            " per motor) is below the model's " + formatPrintf("%.1f g", lowest.thrust_n / kNewtonPerGramForce) +
            " at its lowest PWM, " + formatPrintf("%.0f us", domain.pwm_min_us) +
            ": the hover point lies below the measured range and is shown at that PWM");
      }
    }
    integrateHover(model, *options.hover, &result);
  }
  return result;
}

}  // namespace fitting
}  // namespace propulsion_estimator
