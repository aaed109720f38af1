#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/units.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;

// The thesis model as a thrust-only stand gives it (`fit_surfaces --without current` and no power
// log): current, power and efficiency `none`, thrust and rpm as in the thesis.
inline pe::PropulsionModel thrustOnlyThesisModel() {
  std::string text = pe::readTextFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  const std::size_t from = text.find("  current:");
  const std::size_t to = text.find("  rpm:");
  text.replace(from, to - from,
               "  current:\n    unit: A\n    none: no current sensor on the stand\n"
               "  power:\n    unit: W\n    none: no current sensor on the stand\n"
               "  efficiency:\n    unit: g/W\n    none: no power without current\n");
  return pe::parseModelYaml(text, "thrust_only.yaml");
}

// The thesis model on the thesis quad, fed at 50 Hz like MAVROS' rc/out; with `effects`, the
// model corrected by them.
class EstimatorFixture {
 public:
  explicit EstimatorFixture(pe::EstimatorConfig config = {}, pe::Vehicle vehicle = pe::Vehicle::quadX(0.225),
                            const pe::effects::ModelEffects& effects = {})
      : model(pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml")).withEffects(effects)),
        estimator(model, std::move(vehicle), std::move(config)) {}

  // Motor outputs at `pwm` on all four motors for `seconds` every `period_s`, with a fresh voltage
  // every second.
  void fly(double pwm, double seconds, double voltage_v = 11.4) {
    const std::vector<std::uint16_t> channels(8, static_cast<std::uint16_t>(pwm));
    for (double end = t + seconds; t < end - 1e-9; t += period_s) {
      if (t - last_battery >= 1.0) {
        estimator.addBattery(t, voltage_v);
        last_battery = t;
      }
      EXPECT_EQ(estimator.addMotorOutputs(t, t, channels.data(), channels.size()), pe::Rejection::kNone) << t;
    }
  }

  // Four motors at `pwm` through the model: the thrust the estimator must find.
  double modelMassKg(double pwm, double voltage_v = 11.4) const {
    pe::OperatingPoint e;
    model.evaluate(pwm, voltage_v, &e);
    return 4.0 * e.thrust_n / pe::kStandardGravity;
  }

  pe::PropulsionModel model;
  pe::Estimator estimator;
  double t = 100.0;
  double period_s = 0.02;  // 50 Hz, like MAVROS' rc/out
  double last_battery = -10.0;
};
