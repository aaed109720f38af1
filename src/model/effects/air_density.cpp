// air_density: the flight's air thinner or denser than the bench's.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace effects {

const EffectDescription& airDensityEffect() {
  static const EffectDescription description = [] {
    EffectDescription d{};
    d.name = "air_density";
    // A rotor at fixed duty and voltage turns where its motor's torque balances the propeller's,
    // kQ rho w^2 + (Kt^2 / R) w = Kt (duty V / R - I0). In air of r times the bench's density the
    // speed rises by y with r x y^2 + y = x + 1, where x = kQ rho_bench w / (Kt^2 / R) is the
    // share of the propeller's load against the motor's speed stiffness on the bench, and thrust
    // goes as r y^2: as rho^1 for a stiff motor (x -> 0), towards rho^0 for a weak one. x grows
    // with speed, x = x_full sqrt(T / T_full), so one parameter holds the whole law: the exponent
    // the law has at the model's full thrust, 1 / (1 + 2 x_full). A power law with one exponent
    // leaves, beside a high site's air, a residual that rises with throttle.
    d.parameter = {"full_thrust_exponent", 0.0, 1.0, 0.0};
    d.signal = Signal::kAirDensity;
    d.meaning =
        "the flight's air is thinner or denser than the bench's: a propeller's thrust at a given speed follows "
        "the density";
    d.separating_flight =
        "fly on another day or site with static pressure and air temperature logged: an air-density loss "
        "follows the air, not the current or the payload";
    d.thrust_factor = [](double value, const ModelEffects& references, const Signals& signals, double thrust_n) {
      if (value <= 0.0) return 1.0;
      // A programming error, not a file's: PropulsionModel and the diagnosis set it.
      if (std::isnan(references.full_thrust_n)) throw std::logic_error("air_density: the model's full thrust is not set");
      const double ratio = signals.value(Signal::kAirDensity) / references.air_reference_density_kg_m3;
      // Capped where the factor is 1 to many digits: x (x + 1) would overflow for a tiny parameter.
      const double x_full = std::min(1e9, (1.0 / value - 1.0) / 2.0);
      const double x = x_full * std::sqrt(std::max(thrust_n, 0.0) / references.full_thrust_n);
      // y = (sqrt(1 + 4 r x (x + 1)) - 1) / (2 r x), in the form that holds at x = 0.
      const double speed = 2.0 * (x + 1.0) / (1.0 + std::sqrt(1.0 + 4.0 * ratio * x * (x + 1.0)));
      return ratio * speed * speed;
    };
    // The battery current at the sensed voltage measures electrical power, and at a given power
    // momentum theory gives T proportional to (rho P^2)^(1/3): the current view sees
    // (rho / rho_bench)^(1/3) whatever the motor.
    d.current_view_factor = [](double value, const ModelEffects& references, const Signals& signals) {
      return value > 0.0 ? std::cbrt(signals.value(Signal::kAirDensity) / references.air_reference_density_kg_m3) : 1.0;
    };
    // The RPM view reads thrust at the flight's density (thrust at a given speed follows it): it
    // already holds what this effect corrects.
    d.rpm_view_exponent = [](double) { return 0.0; };
    // The reference is the model's bench air (metadata), not a key of the effect's entry.
    d.reference = {nullptr, &ModelEffects::air_reference_density_kg_m3, 0.3, 1.6,
                   "the model has no bench air (metadata bench_air_temperature_c, bench_air_pressure_pa)"};
    d.describe_reference = [](const ModelEffects& effects) {
      // The bench's air, or the reference flights' whose thrust level a corrected model holds.
      return ", reference air " + formatPrintf("%.4f", effects.air_reference_density_kg_m3) + " kg/m^3";
    };
    d.validate_reference = [](const ModelEffects& effects) {
      if (std::isnan(effects.air_reference_density_kg_m3)) {
        throw FieldError("effects.air_density",
                         "needs the bench air of the model's metadata (bench_air_temperature_c, bench_air_pressure_pa) "
                         "as its reference, and the model has none");
      }
      if (!(effects.air_reference_density_kg_m3 > 0.3 && effects.air_reference_density_kg_m3 < 1.6)) {
        throw FieldError("effects.air_density", "the reference air density " +
                                                    formatNumber(effects.air_reference_density_kg_m3) +
                                                    " kg/m^3 (the metadata's bench air, or the motor_reference's air) "
                                                    "is outside 0.3..1.6 kg/m^3");
      }
    };
    return d;
  }();
  return description;
}

}  // namespace effects
}  // namespace propulsion_estimator
