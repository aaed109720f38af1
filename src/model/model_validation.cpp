#include "propulsion_estimator/model/model_validation.h"

#include <cmath>
#include <sstream>

#include "propulsion_estimator/common/field_error.h"

namespace propulsion_estimator {
namespace {

constexpr int kPwmPoints = 36;
constexpr int kVoltagePoints = 15;

double gridValue(double lo, double hi, int k, int n) { return n == 1 ? lo : lo + (hi - lo) * k / (n - 1); }

[[noreturn]] void refuse(Output output, double value, const std::string& unit, double x, double v,
                         const std::string& why) {
  std::ostringstream problem;
  problem << value << " " << unit << " at pwm_us=" << x << ", voltage_v=" << v << ": " << why;
  throw FieldError(std::string("outputs.") + outputName(output), problem.str());
}

}  // namespace

void validateModelOnGrid(const PropulsionModel& model) {
  const ModelDomain& domain = model.domain();
  for (Output output : kAllOutputs) {
    const OutputDefinition& def = model.output(output);
    if (def.source == OutputSource::kNone) continue;
    const bool must_be_positive_at_top = output != Output::kEfficiency;
    double first_denominator = 0.0;
    for (int a = 0; a < kPwmPoints; ++a) {
      const double x = gridValue(domain.pwm_min_us, domain.pwm_max_us, a, kPwmPoints);
      for (int b = 0; b < kVoltagePoints; ++b) {
        const double v = gridValue(domain.voltage_min_v, domain.voltage_max_v, b, kVoltagePoints);
        // Where the bench did not go, a clamped or rejected model is never evaluated.
        if (domain.outside != OutsideDomain::kExtrapolate && !domain.contains(x, v)) continue;
        const double value = model.evaluateRaw(output, x, v);
        if (!std::isfinite(value)) refuse(output, value, def.unit, x, v, "not finite");
        if (def.surface && def.surface->denominator()) {
          const InputScaling& s = def.surface->scaling();
          const double d = def.surface->denominator()->evaluate((x - s.pwm_center_us) / s.pwm_scale_us,
                                                                (v - s.voltage_center_v) / s.voltage_scale_v);
          if (a == 0 && b == 0) first_denominator = d;
          if (d * first_denominator <= 0.0) {
            refuse(output, value, def.unit, x, v, "the denominator changes sign in the domain (a pole)");
          }
        }
        if (!must_be_positive_at_top && value < 0.0) {
          refuse(output, value, def.unit, x, v, "efficiency must not be negative anywhere in the domain");
        }
        if (must_be_positive_at_top && a == kPwmPoints - 1 && value < 0.0) {
          refuse(output, value, def.unit, x, v,
                 std::string(outputName(output)) + " must not be negative at the top of the PWM range");
        }
      }
    }
  }
}

}  // namespace propulsion_estimator
