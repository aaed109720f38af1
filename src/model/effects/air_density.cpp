// air_density: the flight's air thinner or denser than the bench's.
#include <cmath>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace effects {

const EffectDescription& airDensityEffect() {
  static const EffectDescription description = [] {
    EffectDescription d{};
    d.name = "air_density";
    // Thrust at fixed pulse width and voltage scales between rho^0.5 (a light, fast motor gaining
    // speed in thin air) and rho^1 (a stiff motor).
    d.parameter = {"exponent", 0.0, 2.0, 0.0};
    d.signal = Signal::kAirDensity;
    d.meaning =
        "the flight's air is thinner or denser than the bench's: a propeller's thrust at a given speed follows "
        "the density";
    d.separating_flight =
        "fly on another day or site with static pressure and air temperature logged: an air-density loss "
        "follows the air, not the current or the payload";
    d.thrust_factor = [](double value, const ModelEffects& references, const Signals& signals) {
      return std::pow(signals.value(Signal::kAirDensity) / references.bench_air_density_kg_m3, value);
    };
    // The battery current at the sensed voltage measures electrical power, and at a given power
    // momentum theory gives T proportional to (rho P^2)^(1/3): the current view sees
    // (rho / rho_bench)^(1/3) whatever exponent the PWM view was fitted with.
    d.current_view_exponent = [](double value) { return value > 0.0 ? (1.0 / 3.0) / value : 0.0; };
    // The RPM view reads thrust at the flight's density (thrust at a given speed follows it): it
    // already holds what this effect corrects.
    d.rpm_view_exponent = [](double) { return 0.0; };
    // The reference is the model's bench air (metadata), not a key of the effect's entry.
    d.reference = {nullptr, &ModelEffects::bench_air_density_kg_m3, 0.3, 1.6,
                   "the model has no bench air (metadata bench_air_temperature_c, bench_air_pressure_pa)"};
    d.describe_reference = [](const ModelEffects& effects) {
      return ", bench air " + formatPrintf("%.4f", effects.bench_air_density_kg_m3) + " kg/m^3";
    };
    d.validate_reference = [](const ModelEffects& effects) {
      if (std::isnan(effects.bench_air_density_kg_m3)) {
        throw FieldError("effects.air_density",
                         "needs the bench air of the model's metadata (bench_air_temperature_c, bench_air_pressure_pa) "
                         "as its reference, and the model has none");
      }
      if (!(effects.bench_air_density_kg_m3 > 0.3 && effects.bench_air_density_kg_m3 < 1.6)) {
        throw FieldError("effects.air_density", "the bench air density " + formatNumber(effects.bench_air_density_kg_m3) +
                                                    " kg/m^3 of the model's metadata is outside 0.3..1.6 kg/m^3");
      }
    };
    return d;
  }();
  return description;
}

}  // namespace effects
}  // namespace propulsion_estimator
