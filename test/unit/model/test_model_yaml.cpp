#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/model/effect_description.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/common/yaml_map.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

// A small valid model; each test breaks one thing in it.
const std::string kValid = R"(format_version: 1
metadata:
  esc: E
  motor: M
  propeller: P
  bench_air_temperature_c: 20
  bench_air_pressure_pa: 101325
  supply: battery
  source: test
domain:
  pwm_us: [1100, 1900]
  voltage_v: [10, 13]
  outside: reject
outputs:
  thrust:
    unit: N
    scaling: {pwm_center_us: 1500, pwm_scale_us: 400, voltage_center_v: 11.5, voltage_scale_v: 1.5}
    polynomial: {p00: 3.0, p10: 3.0, p01: 0.3}
  current:
    unit: A
    polynomial: {p00: -20, p10: 0.02}
  power:
    unit: W
    derived: voltage*current
  efficiency:
    unit: g/W
    derived: thrust/power
  rpm:
    unit: rpm
    none: no tachometer
)";

std::string replaced(const std::string& from, const std::string& to) {
  std::string text = kValid;
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string refusal(const std::string& text) {
  try {
    pe::parseModelYaml(text, "m.yaml");
  } catch (const pe::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(ModelYaml, AcceptsTheValidModel) {
  const pe::PropulsionModel model = pe::parseModelYaml(kValid, "m.yaml");
  pe::OperatingPoint e;
  ASSERT_TRUE(model.evaluate(1500.0, 11.5, &e));
  EXPECT_DOUBLE_EQ(e.thrust_n, 3.0);
  EXPECT_DOUBLE_EQ(e.current_a, 10.0);
  EXPECT_DOUBLE_EQ(e.power_w, 115.0);
  EXPECT_DOUBLE_EQ(e.efficiency_n_per_w, 3.0 / 115.0);
  EXPECT_TRUE(std::isnan(e.rpm));
  EXPECT_FALSE(model.evaluate(1950.0, 11.5, &e)) << "reject policy";
}

TEST(ModelYaml, RefusesUnknownKey) {
  EXPECT_EQ(refusal(replaced("  supply: battery", "  supply: battery\n  colour: red")),
            "m.yaml:9: metadata.colour: unknown key (allowed: esc, motor, propeller, bench_air_temperature_c, "
            "bench_air_pressure_pa, supply, source)");
  EXPECT_EQ(refusal(replaced("p01: 0.3}", "p01: 0.3, q11: 1}")),
            "m.yaml:18: outputs.thrust.polynomial.q11: unknown key (terms are named p<i><j> for p_ij * x^i * v^j)");
}

TEST(ModelYaml, RefusesMissingKey) {
  EXPECT_EQ(refusal(replaced("  propeller: P\n", "")), "m.yaml:3: metadata.propeller: missing key");
  EXPECT_EQ(refusal(replaced("  rpm:\n    unit: rpm\n    none: no tachometer\n", "")),
            "m.yaml:15: outputs.rpm: missing key");
  EXPECT_EQ(refusal(replaced("    none: no tachometer", "")),
            "m.yaml:29: outputs.rpm.unit: give exactly one of polynomial, numerator+denominator, drive_curve, derived or "
            "none");
}

TEST(ModelYaml, RefusesWrongType) {
  EXPECT_EQ(refusal(replaced("p00: -20", "p00: lots")),
            "m.yaml:21: outputs.current.polynomial.p00: expected a number, got 'lots'");
  EXPECT_EQ(refusal(replaced("pwm_us: [1100, 1900]", "pwm_us: 1100")),
            "m.yaml:11: domain.pwm_us: expected [min, max], got '1100'");
  EXPECT_EQ(refusal(replaced("outside: reject", "outside: wrap")),
            "m.yaml:13: domain.outside: 'wrap' is not one of clamp, extrapolate, reject");
  EXPECT_EQ(refusal(replaced("unit: N", "unit: A")), "m.yaml:16: outputs.thrust.unit: 'A' is not a unit of thrust");
}

TEST(ModelYaml, RefusesAKeyThatIsNotAName) {
  EXPECT_EQ(refusal(replaced("  supply: battery", "  supply: battery\n  [1, 2]: 3")),
            "m.yaml:9: metadata: a key must be a name, got a list");
}

TEST(ModelYaml, RefusesAKeyGivenTwice) {
  EXPECT_EQ(refusal("format_version: 1\n" + kValid), "m.yaml:2: format_version: key given twice (first on line 1)");
  EXPECT_EQ(refusal(replaced("  supply: battery", "  supply: battery\n  'supply': regulated")),
            "m.yaml:9: metadata.supply: key given twice (first on line 8)");
  EXPECT_EQ(refusal(replaced("p01: 0.3}", "p01: 0.3, p10: 4}")),
            "m.yaml:18: outputs.thrust.polynomial.p10: key given twice (first on line 18)");
}

TEST(YamlMap, RefusesAKeyGivenTwiceAnywhereButNotThroughAliases) {
  auto refused = [](const std::string& text) {
    try {
      pe::parseYamlDocument(text, "t.yaml");
    } catch (const pe::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refused("items:\n  - {a: 1}\n  - {a: 1, b: 2,\n     a: 3}\n"),
            "t.yaml:4: items[1].a: key given twice (first on line 3)");
  EXPECT_EQ(refused("a:\n  - [1, {b: {c: 1}}]\n  - [2, {b: {c: 1, c: 2}}]\n"),
            "t.yaml:3: a[1][1].b.c: key given twice (first on line 3)");
  EXPECT_EQ(refused("base: &base {a: 1, b: 2}\nfirst: *base\nsecond: *base\nthird: {a: 1}\n"), "accepted");
  EXPECT_EQ(refused("a: 1\nb: {a: 1}\nc: [{a: 1}, {a: 2}]\n"), "accepted");
}

TEST(ModelYaml, FingerprintIdentifiesTheModelNotItsFile) {
  const pe::PropulsionModel a = pe::parseModelYaml(kValid, "a.yaml");
  const pe::PropulsionModel b = pe::parseModelYaml("# another file, same model\n" + kValid, "/elsewhere/b.yaml");
  const pe::PropulsionModel c = pe::parseModelYaml(replaced("p01: 0.3", "p01: 0.31"), "a.yaml");
  EXPECT_EQ(pe::modelFingerprint(a).size(), 16u);
  EXPECT_EQ(pe::modelFingerprint(a), pe::modelFingerprint(b));
  EXPECT_NE(pe::modelFingerprint(a), pe::modelFingerprint(c));
}

TEST(ModelYaml, RefusesNonFiniteCoefficient) {
  EXPECT_EQ(refusal(replaced("p10: 3.0", "p10: .nan")),
            "m.yaml:18: outputs.thrust.polynomial.p10: expected a finite number, got '.nan'");
  EXPECT_EQ(refusal(replaced("p10: 0.02", "p10: -.inf")),
            "m.yaml:21: outputs.current.polynomial.p10: expected a finite number, got '-.inf'");
}

TEST(ModelYaml, RefusesBenchAirOutsideTheRangesOfAir) {
  // The check is ModelMetadata::validate(), which fit_surfaces applies before it writes a model.
  EXPECT_EQ(refusal(replaced("bench_air_temperature_c: 20", "bench_air_temperature_c: 293.15")),
            "m.yaml:6: metadata.bench_air_temperature_c: 293.15 is not an air temperature in deg C");
  EXPECT_EQ(refusal(replaced("bench_air_pressure_pa: 101325", "bench_air_pressure_pa: 1013.25")),
            "m.yaml:7: metadata.bench_air_pressure_pa: 1013.25 is not an air pressure in Pa");
}

TEST(ModelYaml, RefusesEmptyDomain) {
  EXPECT_EQ(refusal(replaced("voltage_v: [10, 13]", "voltage_v: [13, 13]")),
            "m.yaml:12: domain.voltage_v: empty range [13, 13]");
}

TEST(ModelYaml, RefusesNonFiniteValuesOnTheGrid) {
  // 1 / (x - 1100) is infinite on the first grid point.
  const std::string text = replaced("    polynomial: {p00: -20, p10: 0.02}",
                                    "    numerator: {p00: 1}\n    denominator: {p00: -1100, p10: 1}");
  EXPECT_EQ(refusal(text), "m.yaml: outputs.current: inf A at pwm_us=1100, voltage_v=10: not finite");
}

TEST(ModelYaml, RefusesAPoleInsideTheDomain) {
  // 1 / (x - 1500) crosses zero between two grid points.
  const std::string text = replaced("    polynomial: {p00: -20, p10: 0.02}",
                                    "    numerator: {p00: 1}\n    denominator: {p00: -1500, p10: 1}");
  EXPECT_EQ(refusal(text),
            "m.yaml: outputs.current: 0.0875 A at pwm_us=1511.43, voltage_v=10: the denominator changes sign in the "
            "domain (a pole)");
}

TEST(ModelYaml, RefusesNegativeOutputAtTheTopOfTheDomain) {
  EXPECT_EQ(refusal(replaced("p10: 3.0", "p10: -4.0")),
            "m.yaml: outputs.thrust: -1.3 N at pwm_us=1900, voltage_v=10: thrust must not be negative at the top of "
            "the PWM range");
}

TEST(ModelYaml, RefusesNegativeEfficiencyAnywhere) {
  const std::string text = replaced("    derived: thrust/power", "    polynomial: {p00: 5, p10: -0.01}");
  EXPECT_EQ(refusal(text),
            "m.yaml: outputs.efficiency: -6 g/W at pwm_us=1100, voltage_v=10: efficiency must not be negative "
            "anywhere in the domain");
}

TEST(ModelYaml, RefusesUnreadableAndEmptyFiles) {
  EXPECT_EQ(refusal(""), "m.yaml: the file is empty");
  EXPECT_EQ(refusal("outputs: [1, 2"), "m.yaml:1: not valid YAML: end of sequence flow not found");
  try {
    pe::loadModelFile("/nonexistent/model.yaml");
    FAIL();
  } catch (const pe::InputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/model.yaml: cannot open file");
  }
}

TEST(ModelYaml, RoundTripsThroughTheWriter) {
  for (const std::string& text : {kValid, pe::readTextFile(repoPath("config/e300_dji2212_dji9443.yaml"))}) {
    const pe::PropulsionModel original = pe::parseModelYaml(text, "original");
    const std::string written = pe::modelToYaml(original, "written by the test");
    const pe::PropulsionModel reread = pe::parseModelYaml(written, "reread");
    EXPECT_EQ(pe::modelToYaml(reread, "written by the test"), written);
    EXPECT_EQ(reread.metadata().propeller, original.metadata().propeller);
    EXPECT_EQ(reread.domain().outside, original.domain().outside);
    for (double x : {1200.0, 1450.0, 1900.0}) {
      for (double v : {10.5, 11.7, 12.6}) {
        for (pe::Output output : pe::kAllOutputs) {
          const double a = original.evaluateRaw(output, x, v);
          const double b = reread.evaluateRaw(output, x, v);
          if (std::isnan(a)) {
            EXPECT_TRUE(std::isnan(b));
          } else {
            EXPECT_EQ(a, b) << pe::outputName(output);
          }
        }
      }
    }
  }
}

namespace {

// Every effect on, in the layout of the README; appended to kValid from line 31.
const std::string kAllEffects = R"(effects:
  supply_resistance: {resistance_ohm: 0.035}
  ground_effect: {coefficient_m2: 0.0011, rotor_height_m: 0.05}
  motor_temperature: {per_c: 0.0012, reference_c: 22}
  air_density: {full_thrust_exponent: 0.85}
  thrust_loss: {fraction: 0.04}
  climb_inflow: {per_m_s: 0.03}
  esc_offset: {offset_us: 12}
)";

std::string withEffects(const std::string& effects) { return kValid + "effects:\n" + effects; }

// "supply_resistance, air_density, ...": every effect of the registry, as a refusal lists them.
std::string allEffectNames() {
  std::string names;
  for (const std::string& name : pe::effects::allNames()) names += (names.empty() ? "" : ", ") + name;
  return names;
}

std::string withoutBenchAir() {
  std::string text = replaced("  bench_air_temperature_c: 20\n", "");
  const std::string pressure = "  bench_air_pressure_pa: 101325\n";
  text.replace(text.find(pressure), pressure.size(), "");
  return text;
}

}  // namespace

TEST(ModelYaml, ReadsTheEffectsSection) {
  const pe::PropulsionModel model = pe::parseModelYaml(kValid + kAllEffects, "m.yaml");
  const pe::effects::ModelEffects& fx = model.effects();
  EXPECT_EQ(fx.parameter(pe::effects::Kind::kSupplyResistance), 0.035);
  EXPECT_EQ(fx.parameter(pe::effects::Kind::kGroundEffect), 0.0011);
  EXPECT_EQ(fx.rotor_height_m, 0.05);
  EXPECT_EQ(fx.parameter(pe::effects::Kind::kMotorTemperature), 0.0012);
  EXPECT_EQ(fx.motor_reference_c, 22.0);
  EXPECT_EQ(fx.parameter(pe::effects::Kind::kAirDensity), 0.85);
  EXPECT_DOUBLE_EQ(fx.air_reference_density_kg_m3, model.metadata().benchAirDensity());
  EXPECT_NEAR(fx.air_reference_density_kg_m3, 1.2041, 1e-4);  // 101325 Pa, 20 deg C
  EXPECT_EQ(fx.parameter(pe::effects::Kind::kThrustLoss), 0.04);
  EXPECT_EQ(fx.parameter(pe::effects::Kind::kClimbInflow), 0.03);
  EXPECT_EQ(fx.parameter(pe::effects::Kind::kEscOffset), 12.0);
  EXPECT_TRUE(pe::parseModelYaml(kValid, "m.yaml").effects().empty());
}

TEST(ModelYaml, RoundTripsEveryEffect) {
  // Every effect of the registry on, its parameter and reference inside their ranges.
  pe::effects::ModelEffects all;
  for (pe::effects::Kind kind : pe::effects::kAllKinds) {
    const pe::effects::EffectDescription& description = pe::effects::describe(kind);
    const pe::effects::ParameterSpec& spec = description.parameter;
    all.setParameter(kind, spec.min + 0.375 * (spec.max - spec.min));
    const pe::effects::ReferenceSpec& reference = description.reference;
    if (reference.key) all.*reference.member = reference.min + 0.625 * (reference.max - reference.min);
  }
  const pe::PropulsionModel original = pe::parseModelYaml(kValid, "plain").withEffects(all);
  const std::string written = pe::modelToYaml(original);
  const pe::PropulsionModel reread = pe::parseModelYaml(written, "reread");
  EXPECT_EQ(pe::modelToYaml(reread), written);
  for (pe::effects::Kind kind : pe::effects::kAllKinds) {
    ASSERT_TRUE(original.effects().has(kind)) << pe::effects::kindName(kind);
    EXPECT_EQ(reread.effects().parameter(kind), original.effects().parameter(kind)) << pe::effects::kindName(kind);
  }
  EXPECT_EQ(reread.effects().rotor_height_m, original.effects().rotor_height_m);
  EXPECT_EQ(reread.effects().motor_reference_c, original.effects().motor_reference_c);
  EXPECT_EQ(reread.effects().air_reference_density_kg_m3, original.effects().air_reference_density_kg_m3);
  // A corrected model is another model: a tare taken with the plain one does not apply to it.
  EXPECT_NE(pe::modelFingerprint(reread), pe::modelFingerprint(pe::parseModelYaml(kValid, "plain")));
}

TEST(ModelYaml, WithEffectsAddsTheSectionAndTakesTheBenchAirFromTheMetadata) {
  const pe::PropulsionModel plain = pe::parseModelYaml(kValid, "m.yaml");
  pe::effects::ModelEffects fx;
  fx.setParameter(pe::effects::Kind::kAirDensity, 0.8);
  fx.air_reference_density_kg_m3 = 0.9;  // not the metadata's: overridden
  fx.setParameter(pe::effects::Kind::kThrustLoss, 0.05);
  const pe::PropulsionModel corrected = plain.withEffects(fx);
  EXPECT_DOUBLE_EQ(corrected.effects().air_reference_density_kg_m3, plain.metadata().benchAirDensity());
  const std::string written = pe::modelToYaml(corrected);
  EXPECT_NE(written.find("effects:\n  air_density: {full_thrust_exponent: 0.8}\n  thrust_loss: {fraction: 0.05}\n"),
            std::string::npos)
      << written;
  EXPECT_EQ(pe::parseModelYaml(written, "corrected").effects().parameter(pe::effects::Kind::kThrustLoss), 0.05);
  EXPECT_TRUE(plain.effects().empty()) << "withEffects returns a copy";
}

TEST(ModelYaml, RefusesAnUnknownEffectOrKey) {
  EXPECT_EQ(refusal(withEffects("  thrust_loss: {fraction: 0.04}\n  wind: {speed_m_s: 3}\n")),
            "m.yaml:33: effects.wind: unknown key (allowed: " + allEffectNames() + ")");
  EXPECT_EQ(refusal(withEffects("  thrust_loss: {fraction: 0.04, percent: 4}\n")),
            "m.yaml:32: effects.thrust_loss.percent: unknown key (allowed: fraction)");
  EXPECT_EQ(refusal(withEffects("  ground_effect: {coefficient_m2: 0.001, rotor_height_m: 0.05, strength: 1}\n")),
            "m.yaml:32: effects.ground_effect.strength: unknown key (allowed: coefficient_m2, rotor_height_m)");
}

TEST(ModelYaml, RefusesAnEffectWithoutItsParameterOrReference) {
  EXPECT_EQ(refusal(withEffects("  supply_resistance: {}\n")),
            "m.yaml:32: effects.supply_resistance.resistance_ohm: missing key");
  EXPECT_EQ(refusal(withEffects("  ground_effect: {coefficient_m2: 0.001}\n")),
            "m.yaml:32: effects.ground_effect.rotor_height_m: missing key");
  EXPECT_EQ(refusal(withEffects("  motor_temperature: {per_c: 0.001}\n")),
            "m.yaml:32: effects.motor_temperature.reference_c: missing key");
}

// A bench CSV given as a model reads as one plain scalar: the refusal shows its start, not the file.
TEST(ModelYaml, RefusesACsvShowingItsStartOnly) {
  std::string csv = "time_s,pwm_us,voltage_v,thrust_n\n";
  for (int row = 0; row < 200; ++row) csv += "0.5,1500,11.1,3.2\n";
  const std::string line = refusal(csv);
  // Its first 60 characters (the lines folded into one), then its length: 32 + 200 * (1 + 17).
  EXPECT_EQ(line, "m.yaml:1: document: expected a mapping, got 'time_s,pwm_us,voltage_v,thrust_n 0.5,1500,11.1,3.2 "
                  "0.5,1500,...' (a text of 3632 characters)");
}

TEST(ModelYaml, RefusesAnEffectThatIsNotAMappingOrNotANumber) {
  EXPECT_EQ(refusal(withEffects("  esc_offset: 12\n")), "m.yaml:32: effects.esc_offset: expected a mapping, got '12'");
  EXPECT_EQ(refusal(withEffects("  esc_offset: {offset_us: twelve}\n")),
            "m.yaml:32: effects.esc_offset.offset_us: expected a number, got 'twelve'");
  EXPECT_EQ(refusal(withEffects("  climb_inflow: {per_m_s: .nan}\n")),
            "m.yaml:32: effects.climb_inflow.per_m_s: expected a finite number, got '.nan'");
}

TEST(ModelYaml, RefusesEffectValuesOutsideTheirRanges) {
  // The check is ModelEffects::validate(), located in the file.
  EXPECT_EQ(refusal(withEffects("  thrust_loss: {fraction: 0.04}\n  supply_resistance: {resistance_ohm: 35}\n")),
            "m.yaml:33: effects.supply_resistance.resistance_ohm: 35 is outside 0..0.5");
  EXPECT_EQ(refusal(withEffects("  esc_offset: {offset_us: -150}\n")),
            "m.yaml:32: effects.esc_offset.offset_us: -150 is outside -100..100");
  EXPECT_EQ(refusal(withEffects("  motor_temperature: {per_c: 0.001, reference_c: 295}\n")),
            "m.yaml:32: effects.motor_temperature.reference_c: 295 is outside -40..150");
  EXPECT_EQ(refusal(withEffects("  ground_effect: {coefficient_m2: 0.001, rotor_height_m: 5}\n")),
            "m.yaml:32: effects.ground_effect.rotor_height_m: 5 is outside -1..1");
}

TEST(ModelYaml, LoadsAModelWithoutBenchAir) {
  const pe::PropulsionModel model = pe::parseModelYaml(withoutBenchAir(), "m.yaml");
  EXPECT_FALSE(model.metadata().hasBenchAir());
  EXPECT_TRUE(std::isnan(model.metadata().benchAirDensity()));
  const std::string written = pe::modelToYaml(model);
  EXPECT_EQ(written.find("bench_air"), std::string::npos) << written;
  EXPECT_EQ(pe::modelToYaml(pe::parseModelYaml(written, "reread")), written);
  // Every effect but air_density is corrected without it.
  EXPECT_EQ(pe::parseModelYaml(withoutBenchAir() + "effects:\n  thrust_loss: {fraction: 0.04}\n", "m.yaml")
                .effects()
                .parameter(pe::effects::Kind::kThrustLoss),
            0.04);
}

TEST(ModelYaml, RefusesAirDensityWithoutBenchAir) {
  EXPECT_EQ(refusal(withoutBenchAir() + "effects:\n  air_density: {full_thrust_exponent: 0.85}\n"),
            "m.yaml:30: effects.air_density: needs the bench air of the model's metadata (bench_air_temperature_c, "
            "bench_air_pressure_pa) as its reference, and the model has none");
  pe::effects::ModelEffects fx;
  fx.setParameter(pe::effects::Kind::kAirDensity, 0.85);
  try {
    pe::parseModelYaml(withoutBenchAir(), "m.yaml").withEffects(fx);
    FAIL() << "accepted";
  } catch (const pe::ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "effects.air_density: needs the bench air of the model's metadata (bench_air_temperature_c, "
                 "bench_air_pressure_pa) as its reference, and the model has none");
  }
}

// air_density's law is scaled by the model's thrust at its top corner (1900 us, 13 V here).
TEST(ModelYaml, RefusesAirDensityOnAModelWithoutThrustAtItsTopCorner) {
  const std::string flat = replaced("{p00: 3.0, p10: 3.0, p01: 0.3}", "{p00: 3.0, p10: 0.0, p01: -3.0}");
  EXPECT_NO_THROW(pe::parseModelYaml(flat, "m.yaml"));
  EXPECT_EQ(refusal(flat + "effects:\n  air_density: {full_thrust_exponent: 0.85}\n"),
            "m.yaml: effects.air_density: needs thrust at the model's highest pulse width and voltage, and the thrust "
            "surface gives 0 N there");
}

TEST(ModelYaml, RefusesHalfTheBenchAir) {
  EXPECT_EQ(refusal(replaced("  bench_air_pressure_pa: 101325\n", "")),
            "m.yaml:3: metadata.bench_air_pressure_pa: missing: bench air is given as temperature and pressure "
            "together, or not at all");
  EXPECT_EQ(refusal(replaced("  bench_air_temperature_c: 20\n", "")),
            "m.yaml:3: metadata.bench_air_temperature_c: missing: bench air is given as temperature and pressure "
            "together, or not at all");
}

namespace {

// A four-motor reference learned from seven healthy flights, without ESC telemetry.
pe::MotorReference sevenFlightReference() {
  return pe::MotorReference{
      {0.27, 0.22, 0.28, 0.23}, {0.004, 0.005, 0.004, 0.005}, 7, {0.037, 0.053, 0.035, 0.051}, {}, {}};
}

}  // namespace

TEST(ModelYaml, RoundTripsTheMotorReference) {
  pe::PropulsionModel model = pe::parseModelYaml(kValid, "m.yaml");
  model.setMotorReference(sevenFlightReference());
  const pe::PropulsionModel back = pe::parseModelYaml(pe::modelToYaml(model), "back.yaml");
  ASSERT_TRUE(back.motorReference());
  EXPECT_EQ(back.motorReference()->flights, 7);
  EXPECT_EQ(back.motorReference()->shares, model.motorReference()->shares);
  EXPECT_EQ(back.motorReference()->share_std, model.motorReference()->share_std);
  EXPECT_EQ(back.motorReference()->gap_std, model.motorReference()->gap_std);
  EXPECT_FALSE(pe::parseModelYaml(kValid, "m.yaml").motorReference());
  EXPECT_TRUE(back.motorReference()->esc_rpm_deviation.empty());
}

TEST(ModelYaml, RoundTripsTheMotorReferencesEscDeviationsAndThrustFactors) {
  pe::PropulsionModel model = pe::parseModelYaml(kValid, "m.yaml");
  pe::MotorReference reference = sevenFlightReference();
  reference.esc_rpm_deviation = {0.012, -0.008, 0.011, -0.009};
  reference.esc_current_deviation = {-0.03, 0.025, -0.028, 0.027};
  reference.thrust_factor = 0.962;
  reference.rpm_thrust_factor = 0.981;
  reference.esc_rpm_level = 1.027;
  model.setMotorReference(reference);
  const pe::PropulsionModel back = pe::parseModelYaml(pe::modelToYaml(model), "back.yaml");
  ASSERT_TRUE(back.motorReference());
  EXPECT_EQ(back.motorReference()->esc_rpm_deviation, reference.esc_rpm_deviation);
  EXPECT_EQ(back.motorReference()->esc_current_deviation, reference.esc_current_deviation);
  EXPECT_EQ(back.motorReference()->thrust_factor, 0.962);
  EXPECT_TRUE(std::isnan(back.motorReference()->current_thrust_factor));
  EXPECT_EQ(back.motorReference()->rpm_thrust_factor, 0.981);
  EXPECT_EQ(back.motorReference()->esc_rpm_level, 1.027);
  EXPECT_EQ(refusal(kValid + "motor_reference: {flights: 3, esc_rpm_level: 0, shares: [0.25, 0.25, 0.25, 0.25], "
                             "share_std: [0, 0, 0, 0], gap_std: [0, 0, 0, 0]}\n"),
            "m.yaml:31: motor_reference.esc_rpm_level: 0 is outside 0.5..1.5");
  EXPECT_EQ(refusal(kValid + "motor_reference: {flights: 3, thrust_factor: 0.2, shares: [0.25, 0.25, 0.25, 0.25], "
                             "share_std: [0, 0, 0, 0], gap_std: [0, 0, 0, 0]}\n"),
            "m.yaml:31: motor_reference.thrust_factor: 0.2 is outside 0.5..1.5");
}

// The air and motor warmth the reference's thrust levels were flown in, which later diagnoses and
// the corrected model read the air's and the motors' effects against.
TEST(ModelYaml, RoundTripsTheAirAndMotorTemperatureOfTheMotorReference) {
  pe::PropulsionModel model = pe::parseModelYaml(kValid, "m.yaml");
  pe::MotorReference reference = sevenFlightReference();
  reference.thrust_factor = 0.962;
  reference.air_density_kg_m3 = 1.1873;
  reference.motor_temperature_c = 31.25;
  model.setMotorReference(reference);
  const pe::PropulsionModel back = pe::parseModelYaml(pe::modelToYaml(model), "back.yaml");
  ASSERT_TRUE(back.motorReference());
  EXPECT_EQ(back.motorReference()->air_density_kg_m3, 1.1873);
  EXPECT_EQ(back.motorReference()->motor_temperature_c, 31.25);
  reference.air_density_kg_m3 = pe::kNaN;
  reference.motor_temperature_c = pe::kNaN;
  model.setMotorReference(reference);
  const pe::PropulsionModel without = pe::parseModelYaml(pe::modelToYaml(model), "back.yaml");
  EXPECT_TRUE(std::isnan(without.motorReference()->air_density_kg_m3));
  EXPECT_TRUE(std::isnan(without.motorReference()->motor_temperature_c));
  EXPECT_EQ(refusal(kValid + "motor_reference: {flights: 3, air_density_kg_m3: 12, shares: [0.25, 0.25, 0.25, 0.25], "
                             "share_std: [0, 0, 0, 0], gap_std: [0, 0, 0, 0]}\n"),
            "m.yaml:31: motor_reference.air_density_kg_m3: 12 is outside 0.3..2 kg/m^3");
  EXPECT_EQ(refusal(kValid + "motor_reference: {flights: 3, motor_temperature_c: 400, shares: [0.25, 0.25, 0.25, 0.25], "
                             "share_std: [0, 0, 0, 0], gap_std: [0, 0, 0, 0]}\n"),
            "m.yaml:31: motor_reference.motor_temperature_c: 400 is outside -60..200 deg C");
}

// A corrected model holds the reference flights' thrust level, flown in their air: its air effect
// reads the air as a change from that air, and from the bench's without it.
TEST(ModelYaml, TheAirEffectReadsTheAirAgainstTheMotorReferencesAir) {
  pe::PropulsionModel model = pe::parseModelYaml(kValid, "m.yaml");
  const double bench = model.metadata().benchAirDensity();
  EXPECT_EQ(model.effects().air_reference_density_kg_m3, bench);
  pe::MotorReference reference = sevenFlightReference();
  reference.air_density_kg_m3 = 1.105;
  model.setMotorReference(reference);
  EXPECT_EQ(model.effects().air_reference_density_kg_m3, 1.105);
  EXPECT_EQ(model.withEffects(model.effects()).effects().air_reference_density_kg_m3, 1.105);
  pe::effects::ModelEffects air = model.effects();
  air.setParameter(pe::effects::Kind::kAirDensity, 0.6);
  EXPECT_EQ(pe::effects::describeParameters(pe::effects::Kind::kAirDensity, air),
            "full_thrust_exponent 0.6, reference air 1.1050 kg/m^3");  // as the node logs it
  EXPECT_EQ(pe::parseModelYaml(pe::modelToYaml(model), "back.yaml").effects().air_reference_density_kg_m3, 1.105);
  reference.air_density_kg_m3 = pe::kNaN;
  model.setMotorReference(reference);
  EXPECT_EQ(model.effects().air_reference_density_kg_m3, bench);
  model.setMotorReference(std::nullopt);
  EXPECT_EQ(model.effects().air_reference_density_kg_m3, bench);
}

TEST(ModelYaml, RefusesAMotorReferenceThatIsNotOne) {
  EXPECT_EQ(refusal(kValid + "motor_reference: {flights: 7, shares: [0.3, 0.3, 0.3, 0.3], share_std: [0, 0, 0, 0], "
                             "gap_std: [0, 0, 0, 0]}\n"),
            "m.yaml:31: motor_reference.shares: they sum to 1.2000, not 1");
  EXPECT_EQ(refusal(kValid + "motor_reference: {flights: 2, shares: [0.25, 0.25, 0.25, 0.25], share_std: [0, 0, 0, 0], "
                             "gap_std: [0, 0, 0, 0]}\n"),
            "m.yaml:31: motor_reference.flights: 2 is fewer than the 3 needed");
  EXPECT_EQ(refusal(kValid + "motor_reference: {flights: 3, shares: [0.25, 0.25, 0.25, 0.25], share_std: [0, 0], "
                             "gap_std: [0, 0, 0, 0]}\n"),
            "m.yaml:31: motor_reference.share_std: 2 and gap_std 4 values for 4 shares");
  EXPECT_EQ(refusal(kValid + "motor_reference: {flights: 3, shares: [0.25, 0.25, 0.25, 0.25], share_std: [0, 0, 0, 0], "
                             "gap_std: [0, 0, 0, 0], esc_rpm_deviation: [0, 0, 0, 0]}\n"),
            "m.yaml:31: motor_reference.esc_current_deviation: missing key");
  EXPECT_EQ(refusal(kValid + "motor_reference: {flights: 3, shares: [0.25, 0.25, 0.25, 0.25], share_std: [0, 0, 0, 0], "
                             "gap_std: [0, 0, 0, 0], esc_rpm_deviation: [0, 0], esc_current_deviation: [0, 0]}\n"),
            "m.yaml:31: motor_reference.esc_rpm_deviation: 2 and esc_current_deviation 2 values for 4 shares (none or "
            "one per motor, both)");
  EXPECT_EQ(refusal(kValid + "motor_reference: {flights: 3, shares: [0.25, 0.25, 0.25, 0.25], share_std: [0, 0, 0, 0], "
                             "gap_std: [0, 0, 0, 0], esc_rpm_deviation: [0, 0.7, 0, 0], esc_current_deviation: [0, 0, "
                             "0, 0]}\n"),
            "m.yaml:31: motor_reference.esc_rpm_deviation[1]: 0.7 is outside -0.5..0.5");
}
