// climb_inflow: the thrust lost to the axial inflow of a climb.
#include <algorithm>
#include <cmath>

#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace effects {

const EffectDescription& climbInflowEffect() {
  static const EffectDescription description = [] {
    EffectDescription d{};
    d.name = "climb_inflow";
    // Momentum theory gives about v / (2 v_hover) per m/s, a few % per m/s.
    d.parameter = {"per_m_s", -0.1, 0.3, 0.0};
    // The axial flow through the discs: a climb, and in forward flight the disc tilted into its
    // motion, which momentum theory treats alike (lambda = mu tan(alpha) + lambda_i).
    d.signal = Signal::kAxialSpeed;
    d.meaning =
        "air flowing axially through the rotors (a climb, or the discs tilted into forward flight) lowers the blades' "
        "angle of attack and the thrust; a descent the reverse";
    d.separating_flight =
        "steady climbs and descents at two speeds: climb inflow grows with the speed along the rotors' axes";
    // Momentum theory: a climb's axial inflow lowers the blades' angle of attack, while a slow
    // descent (into the vortex-ring region) barely changes thrust at a given rotor speed.
    d.thrust_factor = [](double value, const ModelEffects&, const Signals& signals, double) {
      return 1.0 - value * std::max(signals.value(Signal::kAxialSpeed), 0.0);
    };
    // Momentum theory gives a climb's loss at constant power about as at constant speed.
    d.current_view_exponent = [](double) { return 1.0; };
    // The inflow lowers the blades' angle of attack at a given speed: the RPM view sees the loss.
    d.rpm_view_exponent = [](double) { return 1.0; };
    d.informative = [](double speed_m_s, double) { return std::abs(speed_m_s) > 0.3; };
    d.uninformative = [](double) {
      return std::string("no weighed flight faster than 0.3 m/s along the rotors' axes (a climb or descent)");
    };
    return d;
  }();
  return description;
}

}  // namespace effects
}  // namespace propulsion_estimator
