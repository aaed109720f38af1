// translational_lift: the thrust rotors gain from the air they meet moving horizontally.
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace effects {

const EffectDescription& translationalLiftEffect() {
  static const EffectDescription description = [] {
    EffectDescription d{};
    d.name = "translational_lift";
    // Momentum theory: a disc moving edgewise at V needs less induced inflow, by about
    // (V / v_h)^2 / 4 of it below the hover induced speed v_h (5-8 m/s on small multicopters): at a
    // fixed rotor speed a few % of thrust at 3 m/s. Negative values stand for a vehicle whose
    // airframe loses more to the flow than its rotors gain.
    d.parameter = {"per_m2_s2", -0.01, 0.03, 0.0};
    d.signal = Signal::kHorizontalSpeed;
    d.meaning =
        "rotors moving horizontally meet more air than their own wake brings: less induced inflow, more thrust at "
        "the same speed";
    d.separating_flight =
        "straight legs at two horizontal speeds at one height and payload: translational lift grows with the square "
        "of the speed";
    // The low-speed law of momentum theory (the induced inflow falls as (V / v_h)^2 / 4); over the
    // ground, since no wind is measured: in wind it is the air speed that counts.
    d.thrust_factor = [](double value, const ModelEffects&, const Signals& signals, double) {
      return 1.0 + value * signals.value(Signal::kHorizontalSpeed) * signals.value(Signal::kHorizontalSpeed);
    };
    // At the rotor's speed the thrust rises while the induced torque (thrust x inflow) hardly
    // moves: the same current lifts more, and the current view errs as the PWM view does.
    d.current_view_exponent = [](double) { return 1.0; };
    // Fresh air through the disc lifts more at a given speed: the RPM view sees the gain.
    d.rpm_view_exponent = [](double) { return 1.0; };
    d.informative = [](double speed_m_s, double) { return speed_m_s > 1.0; };
    d.uninformative = [](double) { return std::string("no weighed flight moving faster than 1 m/s horizontally"); };
    return d;
  }();
  return description;
}

}  // namespace effects
}  // namespace propulsion_estimator
