#include "propulsion_estimator/model/model_yaml.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <regex>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/model/effect_description.h"
#include "propulsion_estimator/model/model_validation.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {
namespace {

constexpr int kFormatVersion = 1;

const char* derivationText(Output output) {
  switch (output) {
    case Output::kEfficiency: return "thrust/power";
    case Output::kPower: return "voltage*current";
    case Output::kCurrent: return "power/voltage";
    default: return "";
  }
}

// Terms are written as p<i><j>: value, the thesis' own notation (p20 is the x^2 coefficient).
Polynomial2D readPolynomial(const YamlMap& map) {
  static const std::regex kTermKey("p([0-9])([0-9])");
  std::vector<PolynomialTerm> terms;
  for (const std::string& key : map.keys()) {
    std::smatch match;
    if (!std::regex_match(key, match, kTermKey)) {
      map.fail(key, "unknown key (terms are named p<i><j> for p_ij * x^i * v^j)");
    }
    terms.push_back({std::stoi(match[1]), std::stoi(match[2]), map.number(key)});
  }
  if (terms.empty()) throw ConfigError(map.source() + ": " + map.path() + ": no terms");
  return Polynomial2D(std::move(terms));
}

// drive_curve: {pwm_zero_us: x0, pwm_full_us: x1, c0: .., c1: .., ...}: y = sum c_k u^k,
// u = min(max(0, PWM - x0), x1 - x0) / 1000 * V; without pwm_full_us the bench never reached full throttle.
DriveCurve readDriveCurve(const YamlMap& map) {
  static const std::regex kCoefficientKey("c([0-9])");
  std::vector<double> coefficients;
  for (const std::string& key : map.keys()) {
    std::smatch match;
    if (key == "pwm_zero_us" || key == "pwm_full_us") continue;
    if (!std::regex_match(key, match, kCoefficientKey) || std::stoi(match[1]) > DriveCurve::kMaxDegree) {
      map.fail(key, "unknown key (a drive curve has pwm_zero_us, pwm_full_us and coefficients c0 to c" +
                        std::to_string(DriveCurve::kMaxDegree) + ")");
    }
    const auto k = static_cast<std::size_t>(std::stoi(match[1]));
    if (coefficients.size() <= k) coefficients.resize(k + 1, 0.0);
    coefficients[k] = map.number(key);
  }
  if (coefficients.empty()) map.fail("c0", "missing: a drive curve needs coefficients c0..");
  const double x0 = map.number("pwm_zero_us");
  double x1 = DriveCurve::kNoFullThrottle;
  if (map.has("pwm_full_us")) {
    x1 = map.number("pwm_full_us");
    if (!(x1 > x0)) map.fail("pwm_full_us", formatNumber(x1) + " us is not above pwm_zero_us " + formatNumber(x0) + " us");
  }
  return DriveCurve(x0, std::move(coefficients), x1);
}

// covered: {pwm_us: [...], voltage_min_v: [...], voltage_max_v: [...]}, one entry per PWM level.
std::vector<CoveredLevel> readCovered(const YamlMap& map) {
  map.allowOnly({"pwm_us", "voltage_min_v", "voltage_max_v"});
  const std::vector<double> pwm = map.numbers("pwm_us");
  const std::vector<double> lo = map.numbers("voltage_min_v");
  const std::vector<double> hi = map.numbers("voltage_max_v");
  if (lo.size() != pwm.size()) map.fail("voltage_min_v", "needs one value per pwm_us level");
  if (hi.size() != pwm.size()) map.fail("voltage_max_v", "needs one value per pwm_us level");
  std::vector<CoveredLevel> covered;
  for (std::size_t k = 0; k < pwm.size(); ++k) covered.push_back({pwm[k], lo[k], hi[k]});
  return covered;
}

void writeCovered(YAML::Emitter& out, const std::vector<CoveredLevel>& covered) {
  out << YAML::Key << "covered" << YAML::Value << YAML::BeginMap;
  for (const char* key : {"pwm_us", "voltage_min_v", "voltage_max_v"}) {
    out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (const CoveredLevel& level : covered) {
      const std::string k = key;
      out << formatNumber(k == "pwm_us" ? level.pwm_us : k == "voltage_min_v" ? level.voltage_min_v : level.voltage_max_v);
    }
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
}

void writeDriveCurve(YAML::Emitter& out, const DriveCurve& curve) {
  out << YAML::Key << "drive_curve" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "pwm_zero_us" << YAML::Value << formatNumber(curve.pwmZeroUs());
  if (std::isfinite(curve.pwmFullUs())) out << YAML::Key << "pwm_full_us" << YAML::Value << formatNumber(curve.pwmFullUs());
  for (std::size_t k = 0; k < curve.coefficients().size(); ++k) {
    out << YAML::Key << "c" + std::to_string(k) << YAML::Value << formatNumber(curve.coefficients()[k]);
  }
  out << YAML::EndMap;
}

InputScaling readScaling(const YamlMap& map) {
  map.allowOnly({"pwm_center_us", "pwm_scale_us", "voltage_center_v", "voltage_scale_v"});
  InputScaling scaling{map.number("pwm_center_us"), map.number("pwm_scale_us"), map.number("voltage_center_v"),
                       map.number("voltage_scale_v")};
  if (scaling.pwm_scale_us <= 0.0) map.fail("pwm_scale_us", "must be positive");
  if (scaling.voltage_scale_v <= 0.0) map.fail("voltage_scale_v", "must be positive");
  return scaling;
}

FitQuality readFit(const YamlMap& map) {
  map.allowOnly({"basis", "pwm_degree", "voltage_degree", "points", "r2", "rmse", "max_error", "held_out_rmse",
                 "grouping", "low_band_rmse", "high_band_rmse"});
  FitQuality fit;
  fit.pwm_degree = map.integer("pwm_degree");
  fit.voltage_degree = map.integer("voltage_degree");
  fit.points = map.integer("points");
  fit.r2 = map.number("r2");
  fit.rmse = map.number("rmse");
  fit.max_error = map.number("max_error");
  fit.held_out_rmse = map.number("held_out_rmse");
  fit.grouping = map.text("grouping");
  fit.basis = map.has("basis") ? map.choice("basis", {"polynomial", "drive_curve"}) : "polynomial";
  fit.low_band_rmse = map.optionalNumber("low_band_rmse");
  fit.high_band_rmse = map.optionalNumber("high_band_rmse");
  return fit;
}

OutputDefinition readOutput(const YamlMap& map, Output output) {
  map.allowOnly(
      {"unit", "polynomial", "numerator", "denominator", "drive_curve", "scaling", "derived", "none", "note", "fit"});
  OutputDefinition def;
  def.unit = map.text("unit");
  if (!unitToSi(output, def.unit)) map.fail("unit", "'" + def.unit + "' is not a unit of " + outputName(output));
  def.note = map.optionalText("note").value_or("");
  const int kinds = map.has("polynomial") + map.has("numerator") + map.has("drive_curve") + map.has("derived") +
                    map.has("none");
  if (kinds != 1) {
    map.fail("unit", "give exactly one of polynomial, numerator+denominator, drive_curve, derived or none");
  }
  if (map.has("denominator") != map.has("numerator")) {
    map.fail(map.has("numerator") ? "numerator" : "denominator", "numerator and denominator go together");
  }
  const InputScaling scaling = map.has("scaling") ? readScaling(map.map("scaling")) : InputScaling{};
  if (map.has("scaling") && !map.has("polynomial") && !map.has("numerator")) {
    map.fail("scaling", "scaling applies to a polynomial surface only");
  }
  try {
    if (map.has("polynomial")) {
      def.source = OutputSource::kSurface;
      def.surface = ResponseSurface(readPolynomial(map.map("polynomial")), scaling);
    } else if (map.has("numerator")) {
      def.source = OutputSource::kSurface;
      def.surface =
          ResponseSurface(readPolynomial(map.map("numerator")), readPolynomial(map.map("denominator")), scaling);
    } else if (map.has("drive_curve")) {
      def.source = OutputSource::kSurface;
      def.surface = ResponseSurface(readDriveCurve(map.map("drive_curve")));
    } else if (map.has("derived")) {
      def.source = OutputSource::kDerived;
      const std::string formula = map.text("derived");
      const std::string expected = derivationText(output);
      if (expected.empty()) map.fail("derived", std::string(outputName(output)) + " cannot be derived");
      if (formula != expected) map.fail("derived", "'" + formula + "': " + outputName(output) + " derives only as " + expected);
    } else {
      def.source = OutputSource::kNone;
      def.note = map.text("none");
    }
  } catch (const std::invalid_argument& e) {
    throw ConfigError(map.source() + ": outputs." + outputName(output) + ": " + e.what());
  }
  if (map.has("fit")) def.fit = readFit(map.map("fit"));
  return def;
}

// effects: {<name>: {<parameter key>: value[, <reference key>: value]}, ...}: the names, keys and
// references of each effect's EffectDescription.
effects::ModelEffects readEffects(const YamlMap& map) {
  map.allowOnly(effects::allNames());
  effects::ModelEffects result;
  for (effects::Kind kind : effects::kAllKinds) {
    const effects::EffectDescription& description = effects::describe(kind);
    const std::optional<YamlMap> entry = map.optionalMap(description.name);
    if (!entry) continue;
    const char* key = description.parameter.key;
    const effects::ReferenceSpec& reference = description.reference;
    if (reference.key) {
      entry->allowOnly({key, reference.key});
      result.*reference.member = entry->number(reference.key);
    } else {
      entry->allowOnly({key});
    }
    result.setParameter(kind, entry->number(key));
  }
  return result;
}

void writeEffects(YAML::Emitter& out, const effects::ModelEffects& fx) {
  out << YAML::Key << "effects" << YAML::Value << YAML::BeginMap;
  for (effects::Kind kind : effects::kAllKinds) {
    const std::optional<double> value = fx.parameter(kind);
    if (!value) continue;
    const effects::EffectDescription& description = effects::describe(kind);
    out << YAML::Key << description.name << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << description.parameter.key << YAML::Value << formatNumber(*value);
    if (const char* key = description.reference.key) {
      out << YAML::Key << key << YAML::Value << formatNumber(fx.*description.reference.member);
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

void writePolynomial(YAML::Emitter& out, const Polynomial2D& polynomial) {
  out << YAML::BeginMap;
  for (const PolynomialTerm& term : polynomial.terms()) {
    out << YAML::Key << "p" + std::to_string(term.pwm_power) + std::to_string(term.voltage_power) << YAML::Value
        << formatNumber(term.coefficient);
  }
  out << YAML::EndMap;
}

}  // namespace

// thrust_from_rpm: T = (n_per_rpm2 n^2 + n_per_rpm n) rho / rho_bench, the bench's air from the metadata.
RpmThrust readRpmThrust(const YamlMap& map, double bench_air_density_kg_m3) {
  map.allowOnly({"n_per_rpm2", "n_per_rpm", "rms_n", "rows"});
  RpmThrust result;
  result.n_per_rpm2 = map.number("n_per_rpm2");
  result.n_per_rpm = map.number("n_per_rpm");
  if (!(result.n_per_rpm2 > 0.0)) map.fail("n_per_rpm2", formatNumber(result.n_per_rpm2) + " is not positive");
  result.rms_n = map.number("rms_n");
  result.rows = map.integer("rows");
  result.bench_air_density_kg_m3 = bench_air_density_kg_m3;
  return result;
}

void writeRpmThrust(YAML::Emitter& out, const RpmThrust& fit) {
  out << YAML::Key << "thrust_from_rpm" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "n_per_rpm2" << YAML::Value << formatNumber(fit.n_per_rpm2);
  out << YAML::Key << "n_per_rpm" << YAML::Value << formatNumber(fit.n_per_rpm);
  out << YAML::Key << "rms_n" << YAML::Value << formatNumber(fit.rms_n);
  out << YAML::Key << "rows" << YAML::Value << fit.rows;
  out << YAML::EndMap;
}

// motor_reference: {flights, shares: [...], share_std: [...], gap_std: [...]}, one entry per motor;
// with ESC telemetry also esc_rpm_deviation, esc_current_deviation and esc_rpm_level; with weighed steady flight
// thrust_factor, current_thrust_factor and rpm_thrust_factor (each where the view exists), and the
// air_density_kg_m3 and motor_temperature_c they were flown in (each where the flights gave it).
MotorReference readMotorReference(const YamlMap& map) {
  map.allowOnly({"flights", "shares", "share_std", "gap_std", "esc_rpm_deviation", "esc_current_deviation",
                 "thrust_factor", "current_thrust_factor", "rpm_thrust_factor", "esc_rpm_level", "air_density_kg_m3",
                 "motor_temperature_c"});
  MotorReference reference;
  reference.flights = map.integer("flights");
  reference.shares = map.numbers("shares");
  reference.share_std = map.numbers("share_std");
  reference.gap_std = map.numbers("gap_std");
  for (const auto& [key, value] : {std::make_pair("thrust_factor", &reference.thrust_factor),
                                   std::make_pair("current_thrust_factor", &reference.current_thrust_factor),
                                   std::make_pair("rpm_thrust_factor", &reference.rpm_thrust_factor),
                                   std::make_pair("esc_rpm_level", &reference.esc_rpm_level),
                                   std::make_pair("air_density_kg_m3", &reference.air_density_kg_m3),
                                   std::make_pair("motor_temperature_c", &reference.motor_temperature_c)}) {
    if (map.has(key)) *value = map.number(key);
  }
  if (map.has("esc_rpm_deviation") || map.has("esc_current_deviation")) {
    reference.esc_rpm_deviation = map.numbers("esc_rpm_deviation");
    reference.esc_current_deviation = map.numbers("esc_current_deviation");
  }
  return reference;
}

void writeMotorReference(YAML::Emitter& out, const MotorReference& reference) {
  out << YAML::Key << "motor_reference" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "flights" << YAML::Value << reference.flights;
  for (const auto& [key, value] : {std::make_pair("thrust_factor", reference.thrust_factor),
                                   std::make_pair("current_thrust_factor", reference.current_thrust_factor),
                                   std::make_pair("rpm_thrust_factor", reference.rpm_thrust_factor),
                                   std::make_pair("esc_rpm_level", reference.esc_rpm_level),
                                   std::make_pair("air_density_kg_m3", reference.air_density_kg_m3),
                                   std::make_pair("motor_temperature_c", reference.motor_temperature_c)}) {
    if (!std::isnan(value)) out << YAML::Key << key << YAML::Value << formatNumber(value);
  }
  std::vector<std::pair<const char*, const std::vector<double>*>> lists = {
      {"shares", &reference.shares}, {"share_std", &reference.share_std}, {"gap_std", &reference.gap_std}};
  if (!reference.esc_rpm_deviation.empty()) {
    lists.push_back({"esc_rpm_deviation", &reference.esc_rpm_deviation});
    lists.push_back({"esc_current_deviation", &reference.esc_current_deviation});
  }
  for (const auto& [key, values] : lists) {
    out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (double v : *values) out << formatNumber(v);
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
}

PropulsionModel parseModelYaml(const std::string& text, const std::string& source) {
  const YamlMap root = parseYamlDocument(text, source);
  root.allowOnly({"format_version", "metadata", "domain", "outputs", "effects", "thrust_from_rpm", "motor_reference"});
  if (root.integer("format_version") != kFormatVersion) {
    root.fail("format_version", std::to_string(root.integer("format_version")) + " is not supported (this reader knows " +
                                    std::to_string(kFormatVersion) + ")");
  }

  const YamlMap meta = root.map("metadata");
  meta.allowOnly({"esc", "motor", "propeller", "bench_air_temperature_c", "bench_air_pressure_pa", "supply", "source"});
  ModelMetadata metadata;
  metadata.esc = meta.text("esc");
  metadata.motor = meta.text("motor");
  metadata.propeller = meta.text("propeller");
  metadata.bench_air_temperature_c = meta.optionalNumber("bench_air_temperature_c");
  metadata.bench_air_pressure_pa = meta.optionalNumber("bench_air_pressure_pa");
  validateAt(root, metadata);
  metadata.supply = meta.choice("supply", {"regulated", "battery"}) == "battery" ? SupplyKind::kBattery
                                                                                 : SupplyKind::kRegulated;
  metadata.source = meta.text("source");

  const YamlMap dom = root.map("domain");
  dom.allowOnly({"pwm_us", "voltage_v", "covered", "outside"});
  ModelDomain domain;
  std::tie(domain.pwm_min_us, domain.pwm_max_us) = dom.range("pwm_us");
  std::tie(domain.voltage_min_v, domain.voltage_max_v) = dom.range("voltage_v");
  const std::string outside = dom.choice("outside", {"clamp", "extrapolate", "reject"});
  domain.outside = outside == "clamp" ? OutsideDomain::kClamp
                   : outside == "extrapolate" ? OutsideDomain::kExtrapolate
                                              : OutsideDomain::kReject;
  if (const std::optional<YamlMap> covered = dom.optionalMap("covered")) domain.covered = readCovered(*covered);

  const YamlMap outs = root.map("outputs");
  outs.allowOnly({"thrust", "current", "power", "efficiency", "rpm"});
  std::array<OutputDefinition, kOutputCount> outputs;
  for (Output output : kAllOutputs) outputs[static_cast<int>(output)] = readOutput(outs.map(outputName(output)), output);

  effects::ModelEffects fx;
  if (const std::optional<YamlMap> section = root.optionalMap("effects")) {
    fx = readEffects(*section);
    fx.air_reference_density_kg_m3 = metadata.benchAirDensity();
    validateAt(root, fx);
  }

  std::optional<MotorReference> reference;
  if (const std::optional<YamlMap> section = root.optionalMap("motor_reference")) {
    reference = readMotorReference(*section);
    validateAt(root, *reference);
  }

  try {
    const double bench_density = metadata.benchAirDensity();
    PropulsionModel model(std::move(metadata), domain, std::move(outputs), fx);
    validateModelOnGrid(model);
    if (const std::optional<YamlMap> section = root.optionalMap("thrust_from_rpm")) {
      model.setRpmThrust(readRpmThrust(*section, bench_density));
    }
    model.setMotorReference(reference);
    return model;
  } catch (const ConfigError& e) {
    throw ConfigError(source + ": " + e.what());
  }
}

PropulsionModel loadModelFile(const std::string& path) { return parseModelYaml(readTextFile(path), path); }

std::string modelToYaml(const PropulsionModel& model, const std::string& comment) {
  YAML::Emitter out;
  if (!comment.empty()) out << YAML::Comment(comment) << YAML::Newline;
  out << YAML::BeginMap;
  out << YAML::Key << "format_version" << YAML::Value << kFormatVersion;
  const ModelMetadata& meta = model.metadata();
  out << YAML::Key << "metadata" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "esc" << YAML::Value << meta.esc;
  out << YAML::Key << "motor" << YAML::Value << meta.motor;
  out << YAML::Key << "propeller" << YAML::Value << meta.propeller;
  if (meta.hasBenchAir()) {
    out << YAML::Key << "bench_air_temperature_c" << YAML::Value << formatNumber(*meta.bench_air_temperature_c);
    out << YAML::Key << "bench_air_pressure_pa" << YAML::Value << formatNumber(*meta.bench_air_pressure_pa);
  }
  out << YAML::Key << "supply" << YAML::Value << supplyKindName(meta.supply);
  out << YAML::Key << "source" << YAML::Value << meta.source;
  out << YAML::EndMap;

  const ModelDomain& domain = model.domain();
  out << YAML::Key << "domain" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "pwm_us" << YAML::Value << YAML::Flow << YAML::BeginSeq << formatNumber(domain.pwm_min_us)
      << formatNumber(domain.pwm_max_us) << YAML::EndSeq;
  out << YAML::Key << "voltage_v" << YAML::Value << YAML::Flow << YAML::BeginSeq << formatNumber(domain.voltage_min_v)
      << formatNumber(domain.voltage_max_v) << YAML::EndSeq;
  if (!domain.covered.empty()) writeCovered(out, domain.covered);
  out << YAML::Key << "outside" << YAML::Value << outsideDomainName(domain.outside);
  out << YAML::EndMap;

  out << YAML::Key << "outputs" << YAML::Value << YAML::BeginMap;
  for (Output output : kAllOutputs) {
    const OutputDefinition& def = model.output(output);
    out << YAML::Key << outputName(output) << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "unit" << YAML::Value << def.unit;
    if (!def.note.empty() && def.source != OutputSource::kNone) out << YAML::Key << "note" << YAML::Value << def.note;
    if (def.source == OutputSource::kDerived) out << YAML::Key << "derived" << YAML::Value << derivationText(output);
    if (def.source == OutputSource::kNone) out << YAML::Key << "none" << YAML::Value << def.note;
    if (def.surface && def.surface->driveCurve()) {
      writeDriveCurve(out, *def.surface->driveCurve());
    } else if (def.surface) {
      const InputScaling& s = def.surface->scaling();
      if (!s.isIdentity()) {
        out << YAML::Key << "scaling" << YAML::Value << YAML::Flow << YAML::BeginMap;
        out << YAML::Key << "pwm_center_us" << YAML::Value << formatNumber(s.pwm_center_us);
        out << YAML::Key << "pwm_scale_us" << YAML::Value << formatNumber(s.pwm_scale_us);
        out << YAML::Key << "voltage_center_v" << YAML::Value << formatNumber(s.voltage_center_v);
        out << YAML::Key << "voltage_scale_v" << YAML::Value << formatNumber(s.voltage_scale_v);
        out << YAML::EndMap;
      }
      if (def.surface->denominator()) {
        out << YAML::Key << "numerator" << YAML::Value;
        writePolynomial(out, def.surface->numerator());
        out << YAML::Key << "denominator" << YAML::Value;
        writePolynomial(out, *def.surface->denominator());
      } else {
        out << YAML::Key << "polynomial" << YAML::Value;
        writePolynomial(out, def.surface->numerator());
      }
    }
    if (def.fit) {
      const FitQuality& fit = *def.fit;
      out << YAML::Key << "fit" << YAML::Value << YAML::BeginMap;
      if (fit.basis != "polynomial") out << YAML::Key << "basis" << YAML::Value << fit.basis;
      out << YAML::Key << "pwm_degree" << YAML::Value << fit.pwm_degree;
      out << YAML::Key << "voltage_degree" << YAML::Value << fit.voltage_degree;
      out << YAML::Key << "points" << YAML::Value << fit.points;
      out << YAML::Key << "r2" << YAML::Value << formatNumber(fit.r2);
      out << YAML::Key << "rmse" << YAML::Value << formatNumber(fit.rmse);
      out << YAML::Key << "max_error" << YAML::Value << formatNumber(fit.max_error);
      out << YAML::Key << "held_out_rmse" << YAML::Value << formatNumber(fit.held_out_rmse);
      out << YAML::Key << "grouping" << YAML::Value << fit.grouping;
      if (fit.low_band_rmse) out << YAML::Key << "low_band_rmse" << YAML::Value << formatNumber(*fit.low_band_rmse);
      if (fit.high_band_rmse) out << YAML::Key << "high_band_rmse" << YAML::Value << formatNumber(*fit.high_band_rmse);
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  if (!model.effects().empty()) writeEffects(out, model.effects());
  if (model.rpmThrust()) writeRpmThrust(out, *model.rpmThrust());
  if (model.motorReference()) writeMotorReference(out, *model.motorReference());
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void saveModelFile(const PropulsionModel& model, const std::string& path, const std::string& comment) {
  writeTextFile(path, modelToYaml(model, comment));
}

std::string modelFingerprint(const PropulsionModel& model) {
  // FNV-1a, 64 bit: stable across runs and machines, unlike std::hash.
  std::uint64_t hash = 14695981039346656037ULL;
  for (const unsigned char byte : modelToYaml(model)) {
    hash ^= byte;
    hash *= 1099511628211ULL;
  }
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace propulsion_estimator
