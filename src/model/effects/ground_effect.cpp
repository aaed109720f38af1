// ground_effect: the thrust gain of rotors close to the ground.
#include <algorithm>

#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace effects {

const EffectDescription& groundEffectEffect() {
  static const EffectDescription description = [] {
    EffectDescription d{};
    d.name = "ground_effect";
    // Strength 0..2 of Cheeseman-Bennett on rotors up to 0.3 m in radius.
    d.parameter = {"coefficient_m2", 0.0, 0.02, 0.0};
    d.signal = Signal::kHeight;
    d.meaning = "rotors near the ground push against it: more thrust for the same power within about two diameters";
    d.separating_flight =
        "hover at three heights below two rotor diameters and one well above: ground effect grows as the "
        "rotors near the ground";
    d.thrust_factor = [](double value, const ModelEffects& references, const Signals& signals, double) {
      const double distance = std::max(signals.value(Signal::kHeight) + references.rotor_height_m, kMinGroundDistanceM);
      return 1.0 + value / (distance * distance);
    };
    // Cheeseman-Bennett's ratio is at constant power: the current view sees it as the PWM view does.
    d.current_view_exponent = [](double) { return 1.0; };
    // The ground slows the inflow through a rotor at a given speed: more thrust at that speed.
    d.rpm_view_exponent = [](double) { return 1.0; };
    d.reference = {"rotor_height_m", &ModelEffects::rotor_height_m, -1.0, 1.0, nullptr};
    // Only blocks within two rotor diameters of the ground tell about it.
    d.informative = [](double height_m, double rotor_diameter_m) { return height_m < 2.0 * rotor_diameter_m; };
    d.uninformative = [](double rotor_diameter_m) {
      return "no weighed flight within two rotor diameters (" + formatPrintf("%.2f", 2.0 * rotor_diameter_m) +
             " m) of the ground";
    };
    return d;
  }();
  return description;
}

}  // namespace effects
}  // namespace propulsion_estimator
