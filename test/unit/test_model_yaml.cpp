#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/text_file.h"
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
            "m.yaml:29: outputs.rpm.unit: give exactly one of polynomial, numerator+denominator, derived or none");
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
  } catch (const pe::ConfigError& e) {
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
