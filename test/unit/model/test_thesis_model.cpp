#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/common/yaml_map.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

namespace {

const std::string kModel = "config/e300_dji2212_dji9443.yaml";

struct Maxima {
  double thrust_g = 0, current_a = 0, power_w = 0, efficiency_at_max_power_g_per_w = 0, rpm = 0;
};

// Thesis chapter 7 tabulates the maxima of a 12.6 V sweep over 1200..1900 us.
Maxima maximaAt(const pe::PropulsionModel& model, double voltage_v) {
  Maxima m;
  for (double x = 1200.0; x <= 1900.0; x += 5.0) {
    pe::OperatingPoint e;
    EXPECT_TRUE(model.evaluate(x, voltage_v, &e));
    m.thrust_g = std::max(m.thrust_g, e.thrust_n / pe::kNewtonPerGramForce);
    m.current_a = std::max(m.current_a, e.current_a);
    if (e.power_w > m.power_w) {
      m.power_w = e.power_w;
      m.efficiency_at_max_power_g_per_w = e.efficiency_n_per_w / pe::kNewtonPerGramForce;
    }
    m.rpm = std::max(m.rpm, e.rpm);
  }
  return m;
}

}  // namespace

TEST(ThesisModel, ReproducesChapter7MaximaWithin3Percent) {
  const pe::PropulsionModel model = pe::loadModelFile(repoPath(kModel));
  const Maxima m = maximaAt(model, 12.6);
  EXPECT_NEAR(m.thrust_g, 681.85, 0.03 * 681.85);
  EXPECT_NEAR(m.current_a, 8.89, 0.03 * 8.89);
  EXPECT_NEAR(m.power_w, 112.12, 0.03 * 112.12);
  EXPECT_NEAR(m.efficiency_at_max_power_g_per_w, 6.28, 0.03 * 6.28);
  EXPECT_NEAR(m.rpm, 8682.0, 0.03 * 8682.0);
}

TEST(ThesisModel, HoverPwmGivesAThirdOfTheQuadsWeightPerMotor) {
  const pe::PropulsionModel model = pe::loadModelFile(repoPath(kModel));
  for (double x : {1680.0, 1690.0, 1700.0}) {
    pe::OperatingPoint e;
    ASSERT_TRUE(model.evaluate(x, 11.4, &e));
    const double grams = e.thrust_n / pe::kNewtonPerGramForce;
    EXPECT_GT(grams, 335.0) << x;
    EXPECT_LT(grams, 360.0) << x;
    EXPECT_TRUE(e.in_domain);
  }
}

TEST(ThesisModel, ClampsAndFlagsArmedIdleBelowTheDomain) {
  const pe::PropulsionModel model = pe::loadModelFile(repoPath(kModel));
  pe::OperatingPoint idle, bottom;
  ASSERT_TRUE(model.evaluate(1100.0, 11.4, &idle));
  ASSERT_TRUE(model.evaluate(1200.0, 11.4, &bottom));
  EXPECT_FALSE(idle.in_domain);
  EXPECT_TRUE(bottom.in_domain);
  EXPECT_DOUBLE_EQ(idle.thrust_n, bottom.thrust_n);
}

// A battery sagging below the bench's 10.5 V: the motor sees the duty times the voltage, so the
// clamp keeps that drive at 10.5 V (a lower PWM) rather than the command at a voltage it never had,
// and the battery current is the same power at the lower voltage.
TEST(ThesisModel, ClampsALowVoltageAtTheSameDrive) {
  const pe::PropulsionModel model = pe::loadModelFile(repoPath(kModel));
  pe::OperatingPoint sagged, same_drive;
  ASSERT_TRUE(model.evaluate(1600.0, 9.5, &sagged));
  const double pwm = 1200.0 + 400.0 * 9.5 / 10.5;
  ASSERT_TRUE(model.evaluate(pwm, 10.5, &same_drive));
  EXPECT_FALSE(sagged.in_domain);
  EXPECT_TRUE(same_drive.in_domain);
  EXPECT_NEAR(sagged.thrust_n, same_drive.thrust_n, 1e-9);
  EXPECT_NEAR(sagged.power_w, same_drive.power_w, 1e-9);
  EXPECT_NEAR(sagged.current_a, same_drive.current_a * 10.5 / 9.5, 1e-9);
  pe::OperatingPoint at_command;
  ASSERT_TRUE(model.evaluate(1600.0, 10.5, &at_command));
  EXPECT_LT(sagged.thrust_n, 0.9 * at_command.thrust_n) << "less thrust than the command at the lowest voltage";
  // Above the bench's 12.6 V the same drive is a higher PWM at 12.6 V.
  pe::OperatingPoint full, full_drive;
  ASSERT_TRUE(model.evaluate(1500.0, 12.9, &full));
  ASSERT_TRUE(model.evaluate(1200.0 + 300.0 * 12.9 / 12.6, 12.6, &full_drive));
  EXPECT_NEAR(full.thrust_n, full_drive.thrust_n, 1e-9);
}

// Table 5.4 as printed: poly52 in raw microseconds.
const char* kPrintedTable54 = R"(
    unit: g/W
    polynomial: {p00: -5327, p10: 8.831, p01: 842.5, p20: -0.004666, p11: -1.379, p02: -271.8,
                 p30: 6.128e-7, p21: 7.311e-4, p12: 0.06162, p40: 1.215e-10, p31: -1.118e-7,
                 p22: -3.458e-5, p50: -1.593e-14, p41: -7.093e-12, p32: 6.469e-9})";

TEST(ThesisModel, PrintedEfficiencyTableEvaluatesToLargeNegativeValues) {
  std::string text = pe::readTextFile(repoPath(kModel));
  const std::string derived = "\n    unit: g/W\n    derived: thrust/power";
  const std::size_t at = text.find(derived);
  ASSERT_NE(at, std::string::npos);
  // Evaluate the printed surface alone, without the loader's checks.
  text.replace(at, derived.size(), kPrintedTable54);
  const pe::YamlMap root = pe::parseYamlDocument(text, "printed");
  const pe::YamlMap poly = root.map("outputs").map("efficiency").map("polynomial");
  std::vector<pe::PolynomialTerm> terms;
  for (const std::string& key : poly.keys()) terms.push_back({key[1] - '0', key[2] - '0', poly.number(key)});
  const pe::Polynomial2D printed(terms);
  double lo = 1e300, hi = -1e300;
  for (double x = 1200.0; x <= 1900.0; x += 10.0) {
    for (double v = 10.5; v <= 12.6001; v += 0.3) {
      lo = std::min(lo, printed.evaluate(x, v));
      hi = std::max(hi, printed.evaluate(x, v));
    }
  }
  EXPECT_LT(hi, -20000.0);
  EXPECT_GT(lo, -40000.0);
}

TEST(ThesisModel, LoaderRefusesThePrintedEfficiencyTable) {
  std::string text = pe::readTextFile(repoPath(kModel));
  const std::string derived = "\n    unit: g/W\n    derived: thrust/power";
  text.replace(text.find(derived), derived.size(), kPrintedTable54);
  try {
    pe::parseModelYaml(text, "table54.yaml");
    FAIL() << "the printed table 5.4 was accepted";
  } catch (const pe::ConfigError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("table54.yaml: outputs.efficiency: -", 0), 0u) << message;
    EXPECT_NE(message.find("g/W at pwm_us=1200, voltage_v=10.5: efficiency must not be negative anywhere in the domain"),
              std::string::npos)
        << message;
  }
}
