#include "propulsion_estimator/model/propulsion_model.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/model/effect_baseline.h"
#include "propulsion_estimator/model/effect_signals.h"

namespace propulsion_estimator {
namespace {

int index(Output output) { return static_cast<int>(output); }

// The single formula each derivable output has.
bool derivable(Output output) {
  return output == Output::kEfficiency || output == Output::kPower || output == Output::kCurrent;
}

}  // namespace

const char* outputName(Output output) {
  switch (output) {
    case Output::kThrust: return "thrust";
    case Output::kCurrent: return "current";
    case Output::kPower: return "power";
    case Output::kEfficiency: return "efficiency";
    case Output::kRpm: return "rpm";
  }
  return "?";
}

std::optional<double> unitToSi(Output output, const std::string& unit) {
  switch (output) {
    case Output::kThrust:
      if (unit == "N") return 1.0;
      if (unit == "g") return kNewtonPerGramForce;
      if (unit == "kgf") return kStandardGravity;
      break;
    case Output::kCurrent:
      if (unit == "A") return 1.0;
      break;
    case Output::kPower:
      if (unit == "W") return 1.0;
      break;
    case Output::kEfficiency:
      if (unit == "N/W") return 1.0;
      if (unit == "g/W") return kNewtonPerGramForce;
      break;
    case Output::kRpm:
      if (unit == "rpm") return 1.0;
      break;
  }
  return std::nullopt;
}

const char* outsideDomainName(OutsideDomain policy) {
  switch (policy) {
    case OutsideDomain::kClamp: return "clamp";
    case OutsideDomain::kExtrapolate: return "extrapolate";
    case OutsideDomain::kReject: return "reject";
  }
  return "?";
}

const char* supplyKindName(SupplyKind supply) { return supply == SupplyKind::kBattery ? "battery" : "regulated"; }

std::pair<double, double> ModelDomain::voltageRange(double pwm_us) const {
  if (covered.empty()) return {voltage_min_v, voltage_max_v};
  if (pwm_us <= covered.front().pwm_us) return {covered.front().voltage_min_v, covered.front().voltage_max_v};
  if (pwm_us >= covered.back().pwm_us) return {covered.back().voltage_min_v, covered.back().voltage_max_v};
  const auto above = std::upper_bound(covered.begin(), covered.end(), pwm_us,
                                      [](double x, const CoveredLevel& level) { return x < level.pwm_us; });
  const CoveredLevel& lo = *(above - 1);
  const CoveredLevel& hi = *above;
  const double t = (pwm_us - lo.pwm_us) / (hi.pwm_us - lo.pwm_us);
  return {lo.voltage_min_v + t * (hi.voltage_min_v - lo.voltage_min_v),
          lo.voltage_max_v + t * (hi.voltage_max_v - lo.voltage_max_v)};
}

bool ModelDomain::contains(double pwm_us, double voltage_v) const {
  if (!(pwm_us >= pwm_min_us && pwm_us <= pwm_max_us && voltage_v >= voltage_min_v && voltage_v <= voltage_max_v)) {
    return false;
  }
  const auto [lo, hi] = voltageRange(pwm_us);
  return voltage_v >= lo && voltage_v <= hi;
}

double ModelDomain::clamp(double* pwm_us, double* voltage_v) const {
  double pwm = std::clamp(*pwm_us, pwm_min_us, pwm_max_us);
  // Beyond the bench's voltages nothing was measured: the motor sees the duty times the supply,
  // so the same drive (PWM above the bench's lowest, times voltage) at the nearest voltage it had.
  // Within them the surfaces' own voltage law holds, at the nearest voltage logged at that PWM.
  const double box_v = std::clamp(*voltage_v, voltage_min_v, voltage_max_v);
  double current_scale = 1.0;
  if (box_v != *voltage_v && *voltage_v > 0.0) {
    pwm = std::clamp(pwm_min_us + (pwm - pwm_min_us) * *voltage_v / box_v, pwm_min_us, pwm_max_us);
    current_scale = box_v / *voltage_v;
  }
  const auto [lo, hi] = voltageRange(pwm);
  *pwm_us = pwm;
  *voltage_v = std::clamp(box_v, lo, hi);
  return current_scale;
}

void ModelDomain::validate() const {
  if (!(pwm_min_us < pwm_max_us) || !(voltage_min_v < voltage_max_v)) {
    throw ConfigError("domain is empty: pwm_us [" + formatNumber(pwm_min_us) + ", " + formatNumber(pwm_max_us) +
                      "], voltage_v [" + formatNumber(voltage_min_v) + ", " + formatNumber(voltage_max_v) + "]");
  }
  for (std::size_t k = 0; k < covered.size(); ++k) {
    const CoveredLevel& level = covered[k];
    const std::string where = "domain.covered: level " + std::to_string(k + 1) + " (" + formatNumber(level.pwm_us) +
                              " us, " + formatNumber(level.voltage_min_v) + " to " +
                              formatNumber(level.voltage_max_v) + " V)";
    if (k > 0 && !(level.pwm_us > covered[k - 1].pwm_us)) throw ConfigError(where + ": PWM levels must ascend");
    if (level.pwm_us < pwm_min_us || level.pwm_us > pwm_max_us) throw ConfigError(where + ": outside pwm_us");
    if (!(level.voltage_min_v <= level.voltage_max_v) || level.voltage_min_v < voltage_min_v ||
        level.voltage_max_v > voltage_max_v) {
      throw ConfigError(where + ": not a voltage range inside voltage_v");
    }
  }
}

double ModelMetadata::benchAirDensity() const {
  if (!hasBenchAir()) return kNaN;
  return effects::airDensityKgM3(*bench_air_pressure_pa, *bench_air_temperature_c);
}

void ModelMetadata::validate() const {
  // A density needs both; one alone is a half-copied metadata block, not a model without bench air.
  if (bench_air_temperature_c.has_value() != bench_air_pressure_pa.has_value()) {
    throw FieldError(bench_air_temperature_c ? "metadata.bench_air_pressure_pa" : "metadata.bench_air_temperature_c",
                     "missing: bench air is given as temperature and pressure together, or not at all");
  }
  // Beyond these the value is in another unit (K, hPa, psi) or a typo, and every density
  // correction made from it would be wrong.
  if (bench_air_temperature_c && !(*bench_air_temperature_c >= -60.0 && *bench_air_temperature_c <= 60.0)) {
    throw FieldError("metadata.bench_air_temperature_c",
                     formatNumber(*bench_air_temperature_c) + " is not an air temperature in deg C");
  }
  if (bench_air_pressure_pa && !(*bench_air_pressure_pa >= 30000.0 && *bench_air_pressure_pa <= 110000.0)) {
    throw FieldError("metadata.bench_air_pressure_pa",
                     formatNumber(*bench_air_pressure_pa) + " is not an air pressure in Pa");
  }
}

PropulsionModel::PropulsionModel(ModelMetadata metadata, ModelDomain domain,
                                 std::array<OutputDefinition, kOutputCount> outputs, effects::ModelEffects effects)
    : metadata_(std::move(metadata)), domain_(domain), outputs_(std::move(outputs)), effects_(effects) {
  // One source for the reference: an effects section cannot claim other bench air than the metadata's.
  effects_.air_reference_density_kg_m3 = metadata_.benchAirDensity();
  domain_.validate();
  for (Output output : kAllOutputs) {
    const OutputDefinition& def = outputs_[index(output)];
    const std::string name = outputName(output);
    const std::optional<double> to_si = unitToSi(output, def.unit);
    if (!to_si) throw ConfigError("outputs." + name + ".unit: '" + def.unit + "' is not a unit of " + name);
    to_si_[index(output)] = *to_si;
    if ((def.source == OutputSource::kSurface) != def.surface.has_value()) {
      throw ConfigError("outputs." + name + ": a surface must be given exactly when the output is a surface");
    }
    if (def.source == OutputSource::kDerived && !derivable(output)) {
      throw ConfigError("outputs." + name + ": " + name + " cannot be derived from other outputs");
    }
  }
  if (outputs_[index(Output::kThrust)].source != OutputSource::kSurface) {
    throw ConfigError("outputs.thrust: thrust must be a surface; it is what the estimator is for");
  }
  const OutputSource current = outputs_[index(Output::kCurrent)].source;
  const OutputSource power = outputs_[index(Output::kPower)].source;
  if (current == OutputSource::kDerived && power != OutputSource::kSurface) {
    throw ConfigError("outputs.current: derived as power/voltage needs power to be a surface");
  }
  if (power == OutputSource::kDerived && current != OutputSource::kSurface) {
    throw ConfigError("outputs.power: derived as voltage*current needs current to be a surface");
  }
  if (outputs_[index(Output::kEfficiency)].source == OutputSource::kDerived && power == OutputSource::kNone) {
    throw ConfigError("outputs.efficiency: derived as thrust/power needs power to be modelled");
  }
  // Surfaces first, then what derives from them; efficiency last because it needs power.
  int next = 0;
  for (Output output : kAllOutputs) {
    if (outputs_[index(output)].source != OutputSource::kDerived) evaluation_order_[next++] = output;
  }
  for (Output output : {Output::kCurrent, Output::kPower, Output::kEfficiency}) {
    if (outputs_[index(output)].source == OutputSource::kDerived) evaluation_order_[next++] = output;
  }
  effects_.full_thrust_n = fullThrustN();
  validateEffects(effects_);
}

double PropulsionModel::fullThrustN() const {
  // The highest voltage logged at the top pulse width: the box's corner may lie where the bench
  // measured nothing.
  return evaluateRaw(Output::kThrust, domain_.pwm_max_us, domain_.voltageRange(domain_.pwm_max_us).second) *
         to_si_[index(Output::kThrust)];
}

void PropulsionModel::validateEffects(const effects::ModelEffects& effects) const {
  effects.validate();
  // air_density's law is scaled by the full thrust (a model file's effects are read without it).
  if (effects.has(effects::Kind::kAirDensity) && !(std::isfinite(effects.full_thrust_n) && effects.full_thrust_n > 0.0)) {
    throw FieldError("effects.air_density", "needs thrust at the model's highest pulse width and voltage, and the "
                                            "thrust surface gives " + formatNumber(effects.full_thrust_n) + " N there");
  }
}

void PropulsionModel::setMotorReference(std::optional<MotorReference> reference) {
  if (reference) reference->validate();
  motor_reference_ = std::move(reference);
  effects_.air_reference_density_kg_m3 = effectBaseline(metadata_, motor_reference_).air_density_kg_m3;
}

PropulsionModel PropulsionModel::withEffects(effects::ModelEffects effects) const {
  PropulsionModel copy = *this;
  effects.air_reference_density_kg_m3 = effectBaseline(metadata_, motor_reference_).air_density_kg_m3;
  effects.full_thrust_n = effects_.full_thrust_n;
  validateEffects(effects);
  copy.effects_ = effects;
  return copy;
}

double PropulsionModel::evaluateSi(Output output, double pwm_us, double voltage_v,
                                   const std::array<double, kOutputCount>& done) const {
  const OutputDefinition& def = outputs_[index(output)];
  switch (def.source) {
    case OutputSource::kSurface:
      return def.surface->evaluate(pwm_us, voltage_v) * to_si_[index(output)];
    case OutputSource::kNone:
      return kNaN;
    case OutputSource::kDerived:
      break;
  }
  switch (output) {
    case Output::kPower: return voltage_v * done[index(Output::kCurrent)];
    case Output::kCurrent: return voltage_v > 0.0 ? done[index(Output::kPower)] / voltage_v : 0.0;
    default: {
      const double power = done[index(Output::kPower)];
      return power > 0.0 ? done[index(Output::kThrust)] / power : 0.0;
    }
  }
}

std::array<double, kOutputCount> PropulsionModel::computeSi(double pwm_us, double voltage_v) const {
  std::array<double, kOutputCount> si{};
  for (Output output : evaluation_order_) {
    const double value = evaluateSi(output, pwm_us, voltage_v, si);
    // Floor a finite dip below zero; a non-finite value stays visible to the caller.
    si[index(output)] = (output != Output::kEfficiency && value < 0.0 && std::isfinite(value)) ? 0.0 : value;
  }
  return si;
}

bool PropulsionModel::evaluate(double pwm_us, double voltage_v, OperatingPoint* estimate) const {
  const bool inside = domain_.contains(pwm_us, voltage_v);
  double current_scale = 1.0;
  if (!inside) {
    if (domain_.outside == OutsideDomain::kReject) return false;
    if (domain_.outside == OutsideDomain::kClamp) current_scale = domain_.clamp(&pwm_us, &voltage_v);
  }
  std::array<double, kOutputCount> si = computeSi(pwm_us, voltage_v);
  si[index(Output::kCurrent)] *= current_scale;
  estimate->thrust_n = si[index(Output::kThrust)];
  estimate->current_a = si[index(Output::kCurrent)];
  estimate->power_w = si[index(Output::kPower)];
  estimate->efficiency_n_per_w = si[index(Output::kEfficiency)];
  estimate->rpm = si[index(Output::kRpm)];
  estimate->in_domain = inside;
  return true;
}

double PropulsionModel::evaluateRaw(Output output, double pwm_us, double voltage_v) const {
  const OutputDefinition& def = outputs_[index(output)];
  if (def.source == OutputSource::kSurface) return def.surface->evaluate(pwm_us, voltage_v);
  return computeSi(pwm_us, voltage_v)[index(output)] / to_si_[index(output)];
}

}  // namespace propulsion_estimator
