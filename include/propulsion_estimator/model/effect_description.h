#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/model/model_effects.h"

namespace propulsion_estimator {
namespace effects {

/// A value an effect's correction reads beside its fitted parameter, kept in ModelEffects.
struct ReferenceSpec {
  /// Its key in the model file's entry of the effect ("rotor_height_m"); nullptr when it comes from
  /// the model's metadata instead (the bench air of air_density) or the effect has none.
  const char* key = nullptr;
  double ModelEffects::*member = nullptr;  ///< where ModelEffects keeps it; nullptr: no reference
  double min = 0.0;                        ///< lowest value accepted in a model file, in the key's unit
  double max = 0.0;                        ///< highest value accepted in a model file, in the key's unit
  /// Why the diagnosis cannot test the effect when the model has no such reference (nullptr: it
  /// always has one, as the rotor height, which defaults to 0).
  const char* missing = nullptr;
};

/// Everything about one effect, in one place (src/model/effects/NAME.cpp): its name, its
/// parameter with unit and plausible range, the signal it reads, its correction of the PWM view
/// (on the inputs or as a factor on thrust), of the current view and of the RPM view, and its report line. Model
/// files, the node, the gap diagnosis and its report read effects only through this.
struct EffectDescription {
  const char* name;         ///< "supply_resistance": model files, reports, the command line
  ParameterSpec parameter;  ///< the fitted parameter, unit in its key
  Signal signal;            ///< what the correction reads besides PWM and voltage (Signal::kNone: nothing)
  /// What the effect is, for the report's "Selected" list: one sentence, no full stop.
  const char* meaning;
  /// The flight that shows this effect's own signature, for the report when the flights cannot
  /// tell it from another effect: one clause, no full stop.
  const char* separating_flight;
  /// PWM view, on the inputs the ESCs see: (pulse width, voltage) corrected with parameter `value`;
  /// nullptr for an effect acting on thrust. Called only with the signal present.
  Inputs (*correct_inputs)(double value, const Inputs& inputs, const Signals& signals);
  /// PWM view, as a factor on one rotor's thrust with parameter `value`, given that rotor's thrust
  /// in N from the surfaces (after the input corrections, before any factor); nullptr for an effect
  /// acting on the inputs. Called only with the signal present.
  double (*thrust_factor)(double value, const ModelEffects& references, const Signals& signals, double thrust_n);
  /// Current view: the exponent on the thrust factor with which the thrust read through the
  /// measured battery current sees the effect (1: as the PWM view; 0: not at all; negative: the
  /// other way). Unused for effects acting on the inputs (the current view takes them through the
  /// surfaces).
  double (*current_view_exponent)(double value);
  /// Current view, for an effect the current view sees by a law of its own rather than as a power
  /// of its thrust factor (nullptr: current_view_exponent says): the factor on the current view's
  /// thrust with parameter `value`. Called only with the signal present.
  double (*current_view_factor)(double value, const ModelEffects& references, const Signals& signals);
  /// RPM view: the exponent on the thrust factor with which the thrust read through each rotor's
  /// measured speed (ESC telemetry, at the flight's air density) sees the effect (1: the air acts on
  /// a rotor at a given speed; 0: the effect only changes the speed, or the view already holds it).
  /// Unused for effects acting on the inputs (the view reads the speed, not the pulse width).
  double (*rpm_view_exponent)(double value);
  ReferenceSpec reference;  ///< the reference it reads beside the parameter, if any
  /// For the gap diagnosis: whether a block with signal `value` tells about the effect (nullptr:
  /// every block with the signal does), given the rotor diameter in m.
  bool (*informative)(double value, double rotor_diameter_m);
  /// Why the effect cannot be tested when too few blocks are informative.
  std::string (*uninformative)(double rotor_diameter_m);
  /// The reference as logs print it beside the parameter (", bench air 1.2041 kg/m^3"); nullptr:
  /// ", <key> <value>" for a reference with a key, nothing without.
  std::string (*describe_reference)(const ModelEffects& effects);
  /// Checks of the reference beyond its range (nullptr: none); throws FieldError.
  void (*validate_reference)(const ModelEffects& effects);
};

/// The description of `kind` (from the registry, effect_list.h).
const EffectDescription& describe(Kind kind);
/// Every effect's name, in kAllKinds order: for key checks and for tools that list the effects.
std::vector<std::string> allNames();

}  // namespace effects
}  // namespace propulsion_estimator
