// motor_temperature: winding resistance and magnet flux following the motor's temperature.
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace effects {

const EffectDescription& motorTemperatureEffect() {
  static const EffectDescription description = [] {
    EffectDescription d{};
    d.name = "motor_temperature";
    // Copper +0.39 %/K and NdFeB flux -0.12 %/K move thrust by under 0.3 %/K.
    d.parameter = {"per_c", -0.01, 0.01, 0.0};
    d.signal = Signal::kMotorTemperature;
    d.meaning = "a warm motor has more winding resistance and less magnet flux than on the bench";
    d.separating_flight =
        "a long hover from cold motors, motor temperature logged: motor heating grows with the motors' "
        "temperature over the flight";
    d.thrust_factor = [](double value, const ModelEffects& references, const Signals& signals, double) {
      return 1.0 + value * (signals.value(Signal::kMotorTemperature) - references.motor_reference_c);
    };
    // A hot motor spins faster at a given duty (weaker flux) but needs more current per newton
    // metre and loses more in its hotter copper: the PWM view under-reads thrust while the
    // current view over-reads it, by about as much (weaker magnets and costlier copper share
    // the change between the two views).
    d.current_view_exponent = [](double) { return -1.0; };
    // A warm motor turns at another speed for the same command; at the speed it does turn, the
    // propeller lifts as on the bench: the RPM view does not see it.
    d.rpm_view_exponent = [](double) { return 0.0; };
    d.reference = {"reference_c", &ModelEffects::motor_reference_c, -40.0, 150.0,
                   "the model has no bench air temperature, the reference of the motor's temperature"};
    return d;
  }();
  return description;
}

}  // namespace effects
}  // namespace propulsion_estimator
