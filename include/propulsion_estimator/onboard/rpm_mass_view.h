#pragma once

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/model/rpm_thrust.h"
#include "propulsion_estimator/onboard/model_check.h"

namespace propulsion_estimator {

/// The mass the hover holds seen through the rotors' measured speeds (ESC telemetry) and the
/// bench's thrust against rpm (RpmThrust), instead of PWM and voltage: a third view, blind to the
/// ESCs' end points, the supply's resistance and the battery's sag. The PWM view's own tilt and
/// acceleration compensation (its mass over its thrust) carries over. Averaged over the hover like
/// the payload estimate, exponentially over `window_s`; fixed memory, O(motors) per message.
class RpmMassView {
 public:
  /// `window_s` > 0, s.
  RpmMassView(RpmThrust thrust, double window_s) : thrust_(thrust), window_s_(window_s) {}

  /// After an accepted RCOut at `now_s`: while hovering with fresh telemetry on every motor of
  /// `check`, one sample; `air_density_kg_m3` NaN for the bench's air.
  void add(double now_s, const EstimatorOutput& output, const ModelCheck& check, double air_density_kg_m3);
  /// Forgets the average.
  void reset();

  double massKg() const { return samples_ > 0 ? mass_kg_ : kNaN; }  ///< kg, NaN before any hover sample
  double hoverS() const { return hover_s_; }  ///< s of hover in the average
  /// The PWM view's mass over the same samples, kg (NaN before any), for comparison.
  double pwmMassKg() const { return samples_ > 0 ? pwm_mass_kg_ : kNaN; }
  /// Whether a sample of the average took the bench's air density for the flight's (no static
  /// pressure and air temperature): on another day's air the mass is off by the density ratio.
  bool atBenchAir() const { return bench_air_samples_ > 0; }

 private:
  RpmThrust thrust_;
  double window_s_;
  double mass_kg_ = 0.0, pwm_mass_kg_ = 0.0, hover_s_ = 0.0, last_s_ = kNaN;
  long samples_ = 0;
  long bench_air_samples_ = 0;
};

}  // namespace propulsion_estimator
