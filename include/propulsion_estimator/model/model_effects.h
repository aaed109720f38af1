#pragma once

#include <array>
#include <optional>
#include <string>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/model/effect_list.h"

namespace propulsion_estimator {
namespace effects {

/// The physical effects that response surfaces measured on a thrust stand leave out, and that
/// the gap diagnosis can name, fit and hand to the node as a model's `effects:` section. One
/// enumerator per line of PE_EFFECT_LIST (effect_list.h); each is described once, in its
/// EffectDescription (effect_description.h).
enum class Kind {
#define PE_EFFECT_ENUMERATOR(enumerator, describer) enumerator,
  PE_EFFECT_LIST(PE_EFFECT_ENUMERATOR)
#undef PE_EFFECT_ENUMERATOR
};
namespace detail {
/// The effects counted: kEffectCount follows the last.
enum EffectCounter {
#define PE_EFFECT_COUNTER(enumerator, describer) enumerator,
  PE_EFFECT_LIST(PE_EFFECT_COUNTER)
#undef PE_EFFECT_COUNTER
  kEffectCount
};
}  // namespace detail
constexpr int kKindCount = detail::kEffectCount;  ///< number of Kind values
/// Every Kind, in declaration order (bit k of a KindMask is kAllKinds[k]).
constexpr std::array<Kind, kKindCount> kAllKinds = {
#define PE_EFFECT_KIND(enumerator, describer) Kind::enumerator,
    PE_EFFECT_LIST(PE_EFFECT_KIND)
#undef PE_EFFECT_KIND
};
static_assert(kKindCount <= 32, "a KindMask holds one bit per effect");

/// What an effect reads besides the ESC pulse width and the sensed battery voltage.
enum class Signal {
  kNone,
  kBatteryCurrent,
  kAirDensity,
  kHeight,
  kMotorTemperature,
  kVerticalSpeed,
  kHorizontalSpeed,
  kAxialSpeed
};
constexpr int kSignalCount = 8;  ///< number of Signal values, kNone included
static_assert(static_cast<int>(Signal::kAxialSpeed) + 1 == kSignalCount, "kSignalCount counts every Signal");

/// The fitted parameter of an effect: its key in model files and reports (with the unit in the
/// name), the range a real vehicle can show, and the value at which the effect vanishes.
struct ParameterSpec {
  const char* key;  ///< "resistance_ohm": the unit is in the key
  double min;       ///< lowest plausible value, in the key's unit
  double max;       ///< highest plausible value, in the key's unit
  double neutral;   ///< the value at which the effect vanishes
};

/// "supply_resistance", "air_density", ...: the names in model files, reports and on the command line.
const char* kindName(Kind kind);
/// The kind named `name`; nullopt for any other string.
std::optional<Kind> kindFromName(const std::string& name);
/// The signal `kind`'s correction reads (Signal::kNone for thrust_loss and esc_offset).
Signal requiredSignal(Kind kind);
/// "battery current", "air density", ...: for messages.
const char* signalName(Signal signal);
/// "battery_current_a", "air_density_kg_m3", ...: the signal with its unit, in files and reports;
/// "none" for Signal::kNone.
const char* signalKey(Signal signal);
/// Every signal but Signal::kNone, in declaration order.
const std::array<Signal, kSignalCount - 1>& allSignals();
/// The fitted parameter of `kind`: key, plausible range and neutral value.
const ParameterSpec& parameterSpec(Kind kind);

/// The signals the corrections read, in SI units (signalKey says which); NaN where a signal is
/// missing or stale. The battery current is drawn by all ESCs, >= 0; the vertical speed is up
/// positive (REP-103); the horizontal speed is over the ground (no wind sensor: the air's is not
/// known); the axial speed is the vehicle's speed along its body z axis (the rotors' axes), climb
/// positive: what flows through the discs axially, in forward flight too (a disc tilted into its
/// motion climbs into it).
struct Signals {
  /// The value of `signal`; NaN for Signal::kNone and for a signal not set.
  double value(Signal signal) const { return values_[static_cast<int>(signal)]; }
  /// Sets `signal` (Signal::kNone stays NaN).
  void set(Signal signal, double value) {
    if (signal != Signal::kNone) values_[static_cast<int>(signal)] = value;
  }

 private:
  static std::array<double, kSignalCount> missing() {
    std::array<double, kSignalCount> values;
    values.fill(kNaN);
    return values;
  }
  std::array<double, kSignalCount> values_ = missing();
};

/// The inputs the ESCs really see.
struct Inputs {
  double pwm_us = 0.0;  ///< us, after the ESC offset
  double voltage_v = 0.0;  ///< V at the ESCs, after the supply resistance
};

/// A model's `effects:` section: each effect is off unless set. The corrections, in the order
/// they apply to one motor's model evaluation at pulse width u and sensed voltage V (each is
/// described in its file in src/model/effects/):
///   esc_offset         u' = u - offset_us
///   supply_resistance  V' = V - resistance_ohm * battery current
///   (the surfaces evaluated at u', V' give thrust T and every other output)
///   air_density        T *= r y^2, r = rho / rho_bench, r x y^2 + y = x + 1, x = x_full sqrt(T / T_full),
///                      x_full = (1 / full_thrust_exponent - 1) / 2   (the motor's torque balance)
///   ground_effect      T *= 1 + coefficient_m2 / max(h + rotor_height_m, kMinGroundDistanceM)^2
///                      (Cheeseman-Bennett's leading term: coefficient = strength * R^2 / 16)
///   thrust_loss        T *= 1 - fraction
///   motor_temperature  T *= 1 + per_c * (T_motor - reference_c)
///   climb_inflow       T *= 1 - per_m_s * max(axial speed, 0)   (climbs; a slow descent barely changes thrust)
///   translational_lift T *= 1 + per_m2_s2 * horizontal speed^2   (below the rotors' hover induced speed)
struct ModelEffects {
  /// Reference of air_density: the model's bench air, or the air of the healthy flights whose
  /// thrust level a correction holds (MotorReference::air_density_kg_m3).
  double air_reference_density_kg_m3 = kNaN;
  /// Reference of air_density: the model's thrust at its highest pulse width and the highest voltage
  /// logged there, N (PropulsionModel::fullThrustN(), set by the model).
  double full_thrust_n = kNaN;
  double rotor_height_m = 0.0;  ///< rotor discs above the height reference, for ground_effect
  double motor_reference_c = kNaN;  ///< reference of motor_temperature

  bool has(Kind kind) const;  ///< whether `kind` is on
  /// The fitted parameter of `kind`, in its ParameterSpec's unit (nullopt when the effect is off).
  std::optional<double> parameter(Kind kind) const;
  /// Switches `kind` on with `value` (or off with nullopt).
  void setParameter(Kind kind, std::optional<double> value);
  bool empty() const;  ///< whether no effect is on

  /// Throws FieldError "effects.<name>.<key>" for a parameter outside its ParameterSpec range or
  /// non-finite, or a reference (bench air density, motor reference temperature) missing while the
  /// effect that needs it is on.
  void validate() const;

 private:
  // Which effects are on (bit(kind), see KindMask) and their parameters (meaningless where off):
  // the node asks empty() for every motor of every RCOut message, and without effects that must
  // cost nothing.
  unsigned on_ = 0;
  std::array<double, kKindCount> values_{};
};

/// "resistance_ohm 0.035", "coefficient_m2 0.0011, rotor_height_m 0.05", ...: the parameter of
/// `kind` and its references as the model file names them, for logs and diagnostics; "off".
std::string describeParameters(Kind kind, const ModelEffects& effects);

/// Below this the ground-effect law leaves its range of validity (a rotor disc on the ground).
constexpr double kMinGroundDistanceM = 0.05;

/// Bit k set: effect kAllKinds[k] (those on whose signal was missing were skipped).
using KindMask = unsigned;
/// The KindMask bit of `kind`.
constexpr KindMask bit(Kind kind) { return 1u << static_cast<unsigned>(kind); }

/// esc_offset and supply_resistance applied to (pwm_us, voltage_v). A correction whose signal is
/// NaN is skipped and its bit set in `*skipped` (when given).
Inputs correctInputs(const ModelEffects& effects, double pwm_us, double voltage_v, const Signals& signals,
                     KindMask* skipped = nullptr);

/// The product of the thrust factors of the effects that are on (1 when none) on a rotor whose
/// surfaces give `thrust_n` N (at the corrected inputs). A factor whose signal is NaN is skipped
/// and its bit set in `*skipped` (when given).
double thrustFactor(const ModelEffects& effects, const Signals& signals, double thrust_n, KindMask* skipped = nullptr);

/// One effect's thrust factor with parameter `value` on a rotor whose surfaces give `thrust_n` N
/// (1 for esc_offset and supply_resistance, which act on the inputs); NaN when its signal is missing.
double singleThrustFactor(Kind kind, double value, const ModelEffects& references, const Signals& signals,
                          double thrust_n);

}  // namespace effects
}  // namespace propulsion_estimator
