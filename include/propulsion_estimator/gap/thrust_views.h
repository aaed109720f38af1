#pragma once

#include <array>

#include "propulsion_estimator/gap/blocks.h"
#include "propulsion_estimator/model/model_effects.h"
#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {
namespace gap {

/// Three views of the vertical thrust a block flew with:
///  - the PWM view: each motor's thrust at its pulse width and the sensed voltage (what the node
///    estimates; outside the domain as the node evaluates it);
///  - the current view: the pulse widths shifted by one common offset until the current surface
///    gives the motors' share of the measured battery current (Block::current_a), and the thrust
///    surface read there;
///  - the RPM view: each motor's thrust at its measured speed (ESC telemetry) through the model's
///    thrust_from_rpm, at the flight's air density.
/// Causes err differently in them: an ESC end-point offset leaves the current and RPM views
/// untouched, an electrical or air-density cause moves the current view two to three times less than the
/// PWM view and the RPM view not at all, a thrust loss or a hidden mass moves all three equally,
/// motor heating moves the first two in opposite directions and not the third.
class ThrustViews {
 public:
  /// `model` must outlive the views; `motors` <= kMaxMotors; `rpm_view` false: the RPM view is
  /// left out (NaN) whatever the model and the blocks hold.
  ThrustViews(const PropulsionModel& model, int motors, bool rpm_view = true);

  /// Vertical thrust of the PWM view with `effects` applied, N.
  double pwmView(const Block& block, const effects::ModelEffects& effects) const;
  /// Vertical thrust of the current view with `effects` applied, N; NaN without a measured
  /// current or a current surface, or when no offset within +-400 us matches the current.
  double currentView(const Block& block, const effects::ModelEffects& effects) const;
  /// Vertical thrust of the RPM view with `effects` applied, N; NaN when left out, without a
  /// thrust_from_rpm in the model or without every motor's speed in the block.
  double rpmView(const Block& block, const effects::ModelEffects& effects) const;
  /// One motor's thrust as the node evaluates it, N (floored at 0): the surfaces' inside the
  /// domain; outside it as the model's `outside` policy says (PropulsionModel::evaluate: clamped or
  /// extrapolated; with `reject`, which the node would refuse, the surfaces' own value).
  double motorThrust(double pwm_us, double voltage_v) const;
  /// One motor's thrust from the surfaces at any point, N (never clamped; floored at 0): what the
  /// bench rows judge.
  double surfaceThrust(double pwm_us, double voltage_v) const;

  /// A per-motor factor on thrust (1 = as modelled), for a motor the balance shows to be off.
  void setMotorScale(int motor, double scale) { motor_scale_[motor] = scale; }
  /// Factors on each view's thrust (1 = as modelled): a healthy vehicle's own level against the
  /// model in each view (MotorReference), so that effects are sought as changes from it. NaN: 1.
  void setLevels(double pwm, double current, double rpm);
  /// Whether the model has a thrust_from_rpm (else the RPM view is NaN).
  bool hasRpmThrust() const { return model_.rpmThrust().has_value(); }
  /// As given.
  int motors() const { return motors_; }

 private:
  // Outside the domain, what the node's evaluation adds to the surfaces' own value at a block's
  // measured inputs (zero inside). The views take the node's value there and an effect's
  // correction as the surfaces' response to the corrected inputs around it: with no effect the
  // views are the node's, and a correction keeps the sensitivity the clamp would flatten.
  struct Offset {
    double thrust_n = 0.0;
    double current_a = 0.0;
  };
  Offset outsideOffset(double pwm_us, double voltage_v) const;
  // The surfaces' thrust plus `offset_n`, floored at 0, N.
  double offsetThrust(double pwm_us, double voltage_v, double offset_n) const;
  std::array<Offset, kMaxMotors> offsets(const Block& block) const;
  // The rotors' thrust along the vertical; with `factors`, each rotor's times the effects' thrust
  // factor at its own thrust (the PWM view).
  double verticalThrust(const Block& block, double pwm_shift_us, const effects::Inputs* inputs, const Offset* offsets,
                        const effects::ModelEffects* factors) const;
  // The product of the thrust-acting effects' factors as the current view (`current_view`) or the
  // RPM view sees them: each effect's current_view_factor where it has one, else its thrust factor
  // raised to the view's exponent.
  static double viewFactor(const effects::ModelEffects& effects, const effects::Signals& signals, bool current_view);

  const PropulsionModel& model_;
  int motors_;
  double thrust_to_si_;
  bool has_current_;
  bool rpm_view_;
  std::array<double, kMaxMotors> motor_scale_;
  double pwm_level_ = 1.0, current_level_ = 1.0, rpm_level_ = 1.0;
};

/// How much of an effect's thrust factor the RPM view sees, as an exponent on it (1: as much as the
/// PWM view; 0: none), given the effect's fitted `parameter`. Only for effects acting on thrust.
double rpmViewExponent(effects::Kind kind, double parameter);

/// How much of an effect's thrust factor the current view sees, as an exponent on it (1: as much
/// as the PWM view; 0: none; negative: the other way), given the effect's fitted `parameter`.
/// Only for effects acting on thrust (not the input corrections, which the current view takes
/// through the surfaces); 0 too for an effect with a current-view law of its own
/// (EffectDescription::current_view_factor: air_density, seen as the cube root of the density ratio).
double currentViewExponent(effects::Kind kind, double parameter);

}  // namespace gap
}  // namespace propulsion_estimator
