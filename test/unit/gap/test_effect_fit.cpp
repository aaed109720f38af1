// Fitting effects' parameters on blocks whose cause is known exactly.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "propulsion_estimator/gap/effect_fit.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;
namespace gap = propulsion_estimator::gap;
namespace fx = propulsion_estimator::effects;

namespace {

// Blocks over a range of pulse widths whose truth is the model with `truth` applied.
std::vector<gap::Block> blocksOf(const gap::ThrustViews& views, const fx::ModelEffects& truth) {
  std::vector<gap::Block> blocks;
  for (int i = 0; i < 40; ++i) {
    gap::Block block;
    block.group = i / 5;
    for (int k = 0; k < 4; ++k) {
      block.pwm_us[k] = 1400.0 + 10.0 * i;
      block.axis_up[k] = 1.0;
    }
    block.voltage_v = 11.0 + 0.02 * i;
    block.signals.set(pe::effects::Signal::kBatteryCurrent, 5.0 + 0.5 * i);
    block.truth_n = 1.0;
    block.truth_n = views.pwmView(block, truth);
    blocks.push_back(block);
  }
  return blocks;
}

std::vector<const gap::Block*> pointers(const std::vector<gap::Block>& blocks) {
  std::vector<const gap::Block*> all;
  for (const gap::Block& block : blocks) all.push_back(&block);
  return all;
}

}  // namespace

TEST(EffectFit, RecoversTwoParametersTogether) {
  const pe::PropulsionModel model = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  const gap::ThrustViews views(model, 4);
  fx::ModelEffects truth;
  truth.setParameter(fx::Kind::kThrustLoss, 0.04);
  truth.setParameter(fx::Kind::kSupplyResistance, 0.06);
  const std::vector<gap::Block> blocks = blocksOf(views, truth);
  const gap::EffectFit fit =
      gap::fitEffects(views, pointers(blocks), {fx::Kind::kThrustLoss, fx::Kind::kSupplyResistance}, fx::ModelEffects());
  EXPECT_NEAR(*fit.effects.parameter(fx::Kind::kThrustLoss), 0.04, 1e-4);
  EXPECT_NEAR(*fit.effects.parameter(fx::Kind::kSupplyResistance), 0.06, 1e-4);
  EXPECT_LT(fit.rms_relative, 1e-6);
  ASSERT_EQ(fit.ci_half.size(), 2u);
}

TEST(EffectFit, StaysInsideThePlausibleRange) {
  const pe::PropulsionModel model = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  const gap::ThrustViews views(model, 4);
  fx::ModelEffects truth;
  truth.setParameter(fx::Kind::kThrustLoss, 0.3);
  const std::vector<gap::Block> blocks = blocksOf(views, truth);
  // An ESC offset cannot reach a 30 % loss within +-100 us: it stops at its bound.
  const gap::EffectFit fit = gap::fitEffects(views, pointers(blocks), {fx::Kind::kEscOffset}, fx::ModelEffects());
  EXPECT_LE(*fit.effects.parameter(fx::Kind::kEscOffset), fx::parameterSpec(fx::Kind::kEscOffset).max);
  EXPECT_GT(fit.rms_relative, 0.01);
}

TEST(EffectFit, WithoutEffectsGivesThePlainResidual) {
  const pe::PropulsionModel model = pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"));
  const gap::ThrustViews views(model, 4);
  fx::ModelEffects truth;
  truth.setParameter(fx::Kind::kThrustLoss, 0.05);
  const std::vector<gap::Block> blocks = blocksOf(views, truth);
  const gap::EffectFit fit = gap::fitEffects(views, pointers(blocks), {}, fx::ModelEffects());
  EXPECT_TRUE(fit.effects.empty());
  EXPECT_NEAR(fit.rms_relative, 1.0 / 0.95 - 1.0, 1e-9);
  EXPECT_NEAR(gap::relative(1.1, blocks[0]) + 1.0, 1.1 / blocks[0].truth_n, 1e-12);
}
