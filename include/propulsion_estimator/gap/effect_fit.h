#pragma once

#include <vector>

#include "propulsion_estimator/gap/blocks.h"
#include "propulsion_estimator/gap/thrust_views.h"
#include "propulsion_estimator/model/model_effects.h"

namespace propulsion_estimator {
namespace gap {

/// Parameters of a set of effects fitted by least squares of the PWM view's relative residual
/// (model / truth - 1), each bounded to its plausible range.
struct EffectFit {
  std::vector<effects::Kind> kinds;  ///< the effects fitted, in the order given
  effects::ModelEffects effects;  ///< the references given, with the fitted parameters set
  std::vector<double> ci_half;    ///< 95 % half-widths, in kinds' order
  double rms_relative = 0.0;      ///< of the fitted residual
};

/// Fits `kinds` on `blocks` (Levenberg-Marquardt, numeric Jacobian). `references` holds the fixed
/// references (bench air density, rotor height, motor reference temperature). The confidence
/// intervals are widened by the blocks per independent group, since neighbouring blocks err
/// together. With `kinds` empty, returns the references and the plain residual.
EffectFit fitEffects(const ThrustViews& views, const std::vector<const Block*>& blocks,
                     const std::vector<effects::Kind>& kinds, const effects::ModelEffects& references);

/// The relative residual of one block: view / truth - 1.
inline double relative(double view_n, const Block& block) { return view_n / block.truth_n - 1.0; }

}  // namespace gap
}  // namespace propulsion_estimator
