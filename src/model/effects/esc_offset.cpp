// esc_offset: the flying ESCs' calibrated end points differ from the bench ESC's.
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace effects {

const EffectDescription& escOffsetEffect() {
  static const EffectDescription description = [] {
    EffectDescription d{};
    d.name = "esc_offset";
    // ESC calibrations differ by tens of microseconds.
    d.parameter = {"offset_us", -100.0, 100.0, 0.0};
    d.signal = Signal::kNone;
    d.meaning =
        "the flying ESCs' calibrated end points differ from the bench ESC's: the same pulse width is another "
        "throttle";
    d.separating_flight =
        "hover with two payloads, the battery current logged: an ESC offset shifts every pulse width by the "
        "same microseconds and the current view does not see it";
    // u' = u - offset: the pulse width the bench ESC would have needed for the same throttle.
    d.correct_inputs = [](double value, const Inputs& inputs, const Signals&) {
      return Inputs{inputs.pwm_us - value, inputs.voltage_v};
    };
    return d;
  }();
  return description;
}

}  // namespace effects
}  // namespace propulsion_estimator
