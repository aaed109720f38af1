// thrust_loss: airframe blockage and rotor-rotor interaction (or an unweighed mass).
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace effects {

const EffectDescription& thrustLossEffect() {
  static const EffectDescription description = [] {
    EffectDescription d{};
    d.name = "thrust_loss";
    // Arms and frame under the rotors take 2-10 %; more is a mis-built vehicle.
    d.parameter = {"fraction", -0.1, 0.4, 0.0};
    d.signal = Signal::kNone;
    d.meaning =
        "arms and frame under the rotors, and rotors in each other's wake, take part of the thrust; an unweighed "
        "mass looks the same";
    d.separating_flight =
        "hover with two payloads at one site and height: a thrust loss takes the same fraction of thrust at "
        "every payload, current, air and height";
    d.thrust_factor = [](double value, const ModelEffects&, const Signals&, double) { return 1.0 - value; };
    // Blockage and interaction act on the air the rotor has already moved: same rotor state,
    // same torque, current and speed, less net force, in every view.
    d.current_view_exponent = [](double) { return 1.0; };
    d.rpm_view_exponent = [](double) { return 1.0; };
    return d;
  }();
  return description;
}

}  // namespace effects
}  // namespace propulsion_estimator
