// Held-out predictions: each block seen through effects fitted on the other units (flights or
// segments), with one law for every load, or with the law's strength free to differ between light
// and heavy loads (the flexible law a second effect must beat, issue 33 point 5).
#include "diagnoser.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {
namespace {

// Neighbouring blocks carry little new information: a stride keeps long flights quick.
std::vector<const Block*> thinned(std::vector<const Block*> training) {
  if (training.size() <= 3000) return training;
  const std::size_t stride = training.size() / 3000 + 1;
  std::vector<const Block*> kept;
  for (std::size_t i = 0; i < training.size(); i += stride) kept.push_back(training[i]);
  return kept;
}

}  // namespace

HeldOutPrediction Diagnoser::predictHeldOut(const std::vector<Kind>& kinds) const {
  const effects::ModelEffects base = references();
  return predictHeldOutWith([&](const std::vector<const Block*>& training) {
    const effects::ModelEffects fitted = fitEffects(views_, thinned(training), kinds, base).effects;
    return EffectsOfBlock([fitted](const Block&) -> const effects::ModelEffects& { return fitted; });
  });
}

// A law that holds at one load and not at another (a supply resistance that rises with the
// current, a thrust loss that follows each rotor's loading, ESCs with their own gain) leaves a
// residual that grows with the load, and a second effect whose signal follows the load (the
// motors' temperature, a flight's air beside its payload) takes it up. Fitted apart below and above
// the training blocks' median load, the same effects take it up themselves.
HeldOutPrediction Diagnoser::predictHeldOutByLoad(const std::vector<Kind>& kinds, const LoadOf& load) const {
  const effects::ModelEffects base = references();
  return predictHeldOutWith([&](const std::vector<const Block*>& training) {
    std::vector<double> loads;
    for (const Block* block : training) loads.push_back(load(*block));
    std::nth_element(loads.begin(), loads.begin() + loads.size() / 2, loads.end());
    const double median = loads[loads.size() / 2];
    std::vector<const Block*> light, heavy;
    for (const Block* block : training) (load(*block) < median ? light : heavy).push_back(block);
    if (light.empty()) light = heavy;
    const effects::ModelEffects light_fit = fitEffects(views_, thinned(light), kinds, base).effects;
    const effects::ModelEffects heavy_fit = fitEffects(views_, thinned(heavy), kinds, base).effects;
    return EffectsOfBlock([load, light_fit, heavy_fit, median](const Block& block) -> const effects::ModelEffects& {
      return load(block) < median ? light_fit : heavy_fit;
    });
  });
}

HeldOutPrediction Diagnoser::predictHeldOutWith(const UnitFit& fit_unit) const {
  HeldOutPrediction prediction;
  prediction.pwm.assign(blocks_.size(), kNaN);
  prediction.current.assign(blocks_.size(), kNaN);
  prediction.rpm.assign(blocks_.size(), kNaN);
  prediction.view_n.assign(blocks_.size(), kNaN);
  for (int unit = 0; unit < units_; ++unit) {
    std::vector<const Block*> training;
    for (std::size_t i = 0; i < blocks_.size(); ++i) {
      if (unit_of_block_[i] != unit) training.push_back(&blocks_[i]);
    }
    const EffectsOfBlock effects_of = fit_unit(training);
    // The current view's residual, and how it moves per ampere the avionics draw beside the motors.
    double sum_rs = 0.0, sum_ss = 0.0;
    std::vector<double> slope(blocks_.size(), kNaN);
    for (std::size_t i = 0; i < blocks_.size(); ++i) {
      if (unit_of_block_[i] != unit) continue;
      const effects::ModelEffects& fitted = effects_of(blocks_[i]);
      const double view = views_.pwmView(blocks_[i], fitted);
      prediction.view_n[i] = view;
      prediction.pwm[i] = relative(view, blocks_[i]);
      prediction.current[i] = relative(views_.currentView(blocks_[i], fitted), blocks_[i]);
      prediction.rpm[i] = relative(views_.rpmView(blocks_[i], fitted), blocks_[i]);
      Block less = blocks_[i];
      less.current_a -= 1.0;
      slope[i] = prediction.current[i] - relative(views_.currentView(less, fitted), blocks_[i]);
      if (std::isfinite(prediction.current[i]) && std::isfinite(slope[i])) {
        sum_rs += prediction.current[i] * slope[i];
        sum_ss += slope[i] * slope[i];
      }
    }
    // The avionics' own draw (flight controller, companion computer, radios, camera) is on the
    // battery current but turns no rotor: a nuisance of the current view, not thrust. It is taken
    // out per held-out unit, alike for every candidate, within 0..kMaxAvionicsCurrentA.
    const double avionics_a = sum_ss > 0.0 ? std::clamp(sum_rs / sum_ss, 0.0, kMaxAvionicsCurrentA) : 0.0;
    for (std::size_t i = 0; i < blocks_.size(); ++i) {
      if (unit_of_block_[i] == unit && std::isfinite(slope[i])) prediction.current[i] -= avionics_a * slope[i];
    }
  }
  return prediction;
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
