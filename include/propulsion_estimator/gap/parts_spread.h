#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/gap/blocks.h"
#include "propulsion_estimator/gap/thrust_views.h"
#include "propulsion_estimator/model/model_effects.h"

namespace propulsion_estimator {
namespace gap {

/// What a healthy vehicle's rotors and ESCs differ from the bench's unit by. The model is one
/// motor, ESC and propeller measured on a stand; the vehicle flies others of the same type, so
/// a thrust loss or an ESC offset of this size describes a vehicle in perfect health as well as
/// any effect would. The diagnosis names an effect only where it changes the thrust by more than
/// these could (effectSizeAgainstParts).
struct PartsSpread {
  /// Fraction: the vehicle's rotors' mean thrust at a given command against the bench unit's.
  /// 0.025: propellers' thrust coefficients and motors' Kv a few per cent apart part to part,
  /// averaged over the vehicle's rotors. Calibrated 2026-11-28 on development seed 4242 of the
  /// family with each motor's own parts (scripts/validate_gap.py --family): its null, centre of
  /// gravity and weak-propeller cases and what other effects' laws left over fitted thrust losses
  /// of up to 2.3 %; the family's real ones start at 3 %.
  double thrust_fraction = 0.025;
  /// us: the ESCs' end points against the bench ESC's (throttle calibration, part spread).
  /// Calibrated likewise: ESC offsets of up to 8.1 us fitted there; the family's real ones start
  /// at 15 us.
  double esc_end_point_us = 10.0;
  /// Fraction: an effect reading a signal whose change the parts' best imitation (a thrust
  /// factor within thrust_fraction plus an ESC shift within esc_end_point_us, one for the whole
  /// vehicle) takes up at most this share of (mean square over the blocks) has a shape no part
  /// gives, and is named however small it is: a ground effect lifts only the blocks near the
  /// ground. Calibrated 2026-11-28 on development seed 421940 of the family with each motor's own
  /// parts: the parts could imitate 0.18-0.23 of the true ground effects' change there and at
  /// least 0.40 of the near-constant effects' (air density, supply resistance, motor heating). It
  /// tells a shape from a constant; what guards against a wrong shaped effect is significance.
  double max_imitated_share = 0.35;

  /// Throws FieldError "parts_thrust_spread" (0..0.5), "parts_esc_spread_us" (0..100 us) or
  /// "parts_max_imitated_share" (0..1) for a value outside its range or non-finite (diagnose_gap's
  /// --parts-thrust-spread, --parts-esc-spread-us, --parts-max-imitated-share).
  void validate() const;
};

/// How far an effect, as fitted, moves the PWM view's thrust beyond what healthy parts could.
struct EffectSize {
  double largest_change_pct = 0.0;  ///< the largest change of the thrust on any block, %
  /// What the parts could change there, % at the block of largest_change_pct: for a thrust
  /// loss the thrust_fraction, for an ESC offset an esc_end_point_us shift of every command (the
  /// same laws as the propellers' and the ESCs' spreads), for any other effect the larger.
  double parts_change_pct = 0.0;
  int blocks_beyond = 0;  ///< blocks where the effect's change exceeds the parts' there
  /// Share of the effect's change (mean square over the blocks) that the parts' best imitation
  /// takes up: a thrust factor within PartsSpread::thrust_fraction plus an ESC shift within
  /// esc_end_point_us, fitted by least squares. 1 for an effect reading no signal (a thrust loss
  /// or an ESC offset: the laws of the parts' spreads, judged by size alone) and for an effect that
  /// changes nothing.
  double imitated_share = 1.0;
};

/// At least this many blocks beyond the parts' spread: one odd block does not carry a name.
constexpr int kMinBlocksBeyondParts = 3;

/// The size of effect `kind` in `fitted` (the effects fitted with it) over `blocks`: on each block
/// the PWM view's thrust with `fitted` against `fitted` without `kind`, and against what `spread`
/// could do there on top of the others; and the share of that change over the blocks the parts
/// could imitate. Blocks where the view gives no positive thrust are skipped.
EffectSize effectSizeAgainstParts(const ThrustViews& views, const std::vector<const Block*>& blocks,
                                  const effects::ModelEffects& fitted, effects::Kind kind,
                                  const PartsSpread& spread);

/// Why effect `kind` fitted at `parameter` (its ParameterSpec unit), of `size`, is not named
/// against `spread`: "" when it is beyond the parts' spread (on kMinBlocksBeyondParts blocks, or
/// by a shape the parts cannot imitate); else one line with the numbers (a change the parts could
/// give on too many blocks; a thrust loss below -thrust_fraction, a gain, which blockage and rotor
/// interaction cannot give).
std::string withinPartsSpread(effects::Kind kind, double parameter, const EffectSize& size, const PartsSpread& spread);

}  // namespace gap
}  // namespace propulsion_estimator
