#include "propulsion_estimator/onboard/rpm_mass_view.h"

#include <algorithm>
#include <cmath>

namespace propulsion_estimator {
namespace {

// A gap counts for at most this much of the average (as the model check's).
constexpr double kMaxStepS = 0.5;

}  // namespace

void RpmMassView::add(double now_s, const EstimatorOutput& output, const ModelCheck& check,
                      double air_density_kg_m3) {
  if (!output.hover.hovering || !(output.totals.thrust_n > 0.0) || !std::isfinite(output.totals.mass_kg)) {
    last_s_ = kNaN;
    return;
  }
  double thrust = 0.0;
  for (std::size_t k = 0; k < output.motors.size(); ++k) {
    const MotorCheck motor = check.motor(k, now_s);
    if (std::isnan(motor.measured_rpm)) {
      last_s_ = kNaN;
      return;
    }
    thrust += thrust_.thrustN(motor.measured_rpm, air_density_kg_m3);
  }
  // The PWM view's vertical share and acceleration compensation: its mass per newton of thrust.
  const double mass = thrust * output.totals.mass_kg / output.totals.thrust_n;
  const double step = std::isnan(last_s_) ? 0.0 : std::min(kMaxStepS, now_s - last_s_);
  const double weight = samples_ == 0 ? 1.0 : 1.0 - std::exp(-step / window_s_);
  mass_kg_ += weight * (mass - mass_kg_);
  pwm_mass_kg_ += weight * (output.totals.mass_kg - pwm_mass_kg_);
  hover_s_ += step;
  last_s_ = now_s;
  ++samples_;
  if (std::isnan(air_density_kg_m3)) ++bench_air_samples_;
}

void RpmMassView::reset() {
  mass_kg_ = pwm_mass_kg_ = hover_s_ = 0.0;
  last_s_ = kNaN;
  samples_ = bench_air_samples_ = 0;
}

}  // namespace propulsion_estimator
