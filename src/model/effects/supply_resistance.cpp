// supply_resistance: wiring, connectors and a power module between the voltage sensor and the ESCs.
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace effects {

const EffectDescription& supplyResistanceEffect() {
  static const EffectDescription description = [] {
    EffectDescription d{};
    d.name = "supply_resistance";
    // Connectors, wires and a power module add 5-50 mOhm; a worn pack or thin harness up to a few hundred.
    d.parameter = {"resistance_ohm", 0.0, 0.5, 0.0};
    d.signal = Signal::kBatteryCurrent;
    d.meaning =
        "wiring, connectors or a power module between the voltage sensor and the ESCs: the ESCs see less voltage "
        "than is measured, more so the more current flows";
    d.separating_flight =
        "hover with two payloads or at two battery charges, the battery current logged: a supply resistance's"
        " loss grows with the current drawn";
    // V' = V - R I: the ESCs see the sensed voltage less the drop across the supply.
    d.correct_inputs = [](double value, const Inputs& inputs, const Signals& signals) {
      return Inputs{inputs.pwm_us, inputs.voltage_v - value * signals.value(Signal::kBatteryCurrent)};
    };
    return d;
  }();
  return description;
}

}  // namespace effects
}  // namespace propulsion_estimator
