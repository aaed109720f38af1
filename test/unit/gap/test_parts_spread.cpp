// An effect is named only beyond what a healthy vehicle's parts differ from the bench unit by.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/model/effect_description.h"
#include "propulsion_estimator/gap/diagnosis.h"
#include "propulsion_estimator/gap/parts_spread.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "test_paths.h"

namespace pe = propulsion_estimator;
namespace gap = propulsion_estimator::gap;
namespace fx = propulsion_estimator::effects;

namespace {

// Hover-like blocks over the pulse widths a hover and a climb use, 11-12 V.
std::vector<gap::Block> hoverBlocks() {
  std::vector<gap::Block> blocks(30);
  for (int i = 0; i < 30; ++i) {
    for (int k = 0; k < 4; ++k) {
      blocks[i].pwm_us[k] = 1500.0 + 5.0 * i;
      blocks[i].axis_up[k] = 1.0;
    }
    blocks[i].voltage_v = 12.0 - 0.03 * i;
  }
  return blocks;
}

class PartsSpreadTest : public ::testing::Test {
 protected:
  PartsSpreadTest()
      : model_(pe::loadModelFile(repoPath("config/e300_dji2212_dji9443.yaml"))), views_(model_, 4),
        blocks_(hoverBlocks()) {
    for (const gap::Block& block : blocks_) all_.push_back(&block);
  }

  // The verdict on `kind` fitted at `value`, against the diagnosis' default spread.
  std::string verdict(fx::Kind kind, double value) const {
    fx::ModelEffects fitted;
    fitted.setParameter(kind, value);
    const gap::PartsSpread spread = gap::DiagnosisConfig().parts_spread;
    return gap::withinPartsSpread(kind, value, gap::effectSizeAgainstParts(views_, all_, fitted, kind, spread), spread);
  }

  pe::PropulsionModel model_;
  gap::ThrustViews views_;
  std::vector<gap::Block> blocks_;
  std::vector<const gap::Block*> all_;
};

TEST_F(PartsSpreadTest, MeasuresAThrustLossAgainstTheThrustSpread) {
  fx::ModelEffects fitted;
  fitted.setParameter(fx::Kind::kThrustLoss, 0.015);
  gap::PartsSpread spread;
  spread.thrust_fraction = 0.02;
  spread.esc_end_point_us = 0.0;
  const gap::EffectSize size = gap::effectSizeAgainstParts(views_, all_, fitted, fx::Kind::kThrustLoss, spread);
  EXPECT_NEAR(size.largest_change_pct, 1.5, 1e-6);
  EXPECT_NEAR(size.parts_change_pct, 2.0, 1e-6);
  EXPECT_EQ(size.blocks_beyond, 0);
  spread.thrust_fraction = 0.01;
  EXPECT_EQ(gap::effectSizeAgainstParts(views_, all_, fitted, fx::Kind::kThrustLoss, spread).blocks_beyond, 30);
  // The ESCs' spread does not excuse a thrust loss: the current and RPM views tell them apart.
  spread.esc_end_point_us = 50.0;
  EXPECT_EQ(gap::effectSizeAgainstParts(views_, all_, fitted, fx::Kind::kThrustLoss, spread).blocks_beyond, 30);
}

TEST_F(PartsSpreadTest, AnEffectReadingASignalIsMeasuredAgainstTheLargerSpread) {
  fx::ModelEffects fitted;
  fitted.setParameter(fx::Kind::kSupplyResistance, 0.01);
  for (gap::Block& block : blocks_) block.signals.set(pe::effects::Signal::kBatteryCurrent, 20.0);
  gap::PartsSpread spread;
  spread.thrust_fraction = 0.0;
  spread.esc_end_point_us = 10.0;
  const gap::EffectSize escs = gap::effectSizeAgainstParts(views_, all_, fitted, fx::Kind::kSupplyResistance, spread);
  spread.thrust_fraction = 0.2;
  const gap::EffectSize both = gap::effectSizeAgainstParts(views_, all_, fitted, fx::Kind::kSupplyResistance, spread);
  EXPECT_GT(escs.parts_change_pct, 0.5);
  EXPECT_NEAR(both.parts_change_pct, 20.0, 1e-6);
  EXPECT_EQ(both.blocks_beyond, 0);
}

TEST_F(PartsSpreadTest, AnEscOffsetWithinTheEscSpreadNeverExceedsIt) {
  fx::ModelEffects fitted;
  fitted.setParameter(fx::Kind::kEscOffset, 8.0);
  gap::PartsSpread spread;
  spread.thrust_fraction = 0.5;  // the propellers' spread does not excuse an ESC offset
  spread.esc_end_point_us = 10.0;
  const gap::EffectSize size = gap::effectSizeAgainstParts(views_, all_, fitted, fx::Kind::kEscOffset, spread);
  EXPECT_GT(size.largest_change_pct, 1.0);
  EXPECT_LT(size.largest_change_pct, size.parts_change_pct);
  EXPECT_EQ(size.blocks_beyond, 0);
}

// The calibration (2026-11-28, development seed 4242 of the family with each motor's own parts;
// parts_spread.h): there the diagnosis fitted thrust losses of up to 2.3 % and ESC offsets of up
// to 8.1 us where none was injected, where the family's true effects start at 3 % and 15 us; the
// defaults (2.5 %, 10 us) lie between. Halving either default names the healthy parts' (the
// first two expectations of each); raising either by half leaves the smallest real ones unnamed.
TEST_F(PartsSpreadTest, TheDefaultsSeparateHealthyPartsFromTheSmallestRealEffects) {
  EXPECT_NE(verdict(fx::Kind::kThrustLoss, 0.023), "");
  EXPECT_NE(verdict(fx::Kind::kThrustLoss, -0.015), "");
  EXPECT_EQ(verdict(fx::Kind::kThrustLoss, 0.03), "");
  EXPECT_NE(verdict(fx::Kind::kEscOffset, 8.1), "");
  EXPECT_NE(verdict(fx::Kind::kEscOffset, -8.1), "");
  EXPECT_EQ(verdict(fx::Kind::kEscOffset, 15.0), "");
  EXPECT_EQ(verdict(fx::Kind::kEscOffset, -15.0), "");
}

TEST_F(PartsSpreadTest, SaysWhyWithTheNumbers) {
  EXPECT_EQ(verdict(fx::Kind::kThrustLoss, 0.015),
            "not named: changes the thrust by at most 1.5 % on any block (2.5 % there is what healthy rotors and "
            "ESCs differ from the bench's by: 2.5 % thrust, 10 us end points); beyond it on 0 blocks, 3 needed");
}

TEST_F(PartsSpreadTest, AThrustGainBeyondTheSpreadIsNotBlockage) {
  EXPECT_EQ(verdict(fx::Kind::kThrustLoss, -0.05),
            "not named: a thrust gain of 5.0 %, which blockage and rotor interaction cannot give (healthy rotors "
            "differ from the bench's by 2.5 %): what another effect's law leaves over, or a bench unit weaker than "
            "the vehicle's");
  EXPECT_NE(verdict(fx::Kind::kThrustLoss, -0.015), "");
}

// A ground effect lifts the few blocks near the ground and no other: a constant thrust factor and
// an ESC shift cannot imitate that, so it is named although it changes no block by the parts'
// 3 %; a change alike on every block, as small, is not.
TEST_F(PartsSpreadTest, AShapeNoPartGivesIsNamedHoweverSmall) {
  for (int i = 0; i < 30; ++i) blocks_[i].signals.set(pe::effects::Signal::kHeight, i % 8 == 3 ? 0.2 : 5.0);  // 4 blocks
  fx::ModelEffects fitted;
  fitted.setParameter(fx::Kind::kGroundEffect, 0.0008);  // 2 % at 0.2 m, 0.003 % at 5 m
  const gap::PartsSpread spread;
  const gap::EffectSize size = gap::effectSizeAgainstParts(views_, all_, fitted, fx::Kind::kGroundEffect, spread);
  EXPECT_NEAR(size.largest_change_pct, 2.0, 0.01);
  EXPECT_EQ(size.blocks_beyond, 0);
  EXPECT_LT(size.imitated_share, 0.2);
  EXPECT_EQ(gap::withinPartsSpread(fx::Kind::kGroundEffect, 0.0008, size, spread), "");

  for (gap::Block& block : blocks_) block.signals.set(pe::effects::Signal::kHeight, 0.4);
  const gap::EffectSize flat = gap::effectSizeAgainstParts(views_, all_, fitted, fx::Kind::kGroundEffect, spread);
  EXPECT_GT(flat.imitated_share, 0.999);
  EXPECT_NE(gap::withinPartsSpread(fx::Kind::kGroundEffect, 0.0008, flat, spread), "");
}

// The calibration of max_imitated_share (2026-11-28, development seed 421940 of the family with
// each motor's own parts, every candidate's parts_imitated_share in report.yaml): the parts could
// imitate 0.18-0.23 of the true ground effects' change (all 0 blocks beyond the parts' size), and
// at least 0.40 of the near-constant effects' (air density, supply resistance, motor heating,
// true or fitted where none was injected). Halving the default leaves the largest ground effect
// there unnamed; raising it by half names an effect the parts imitate as much as the smallest.
TEST_F(PartsSpreadTest, TheImitatedShareSeparatesShapesFromNearConstantChanges) {
  gap::EffectSize size;
  size.largest_change_pct = 1.5;
  size.parts_change_pct = 3.2;
  size.blocks_beyond = 0;
  const gap::PartsSpread spread;
  size.imitated_share = 0.23;
  EXPECT_EQ(gap::withinPartsSpread(fx::Kind::kGroundEffect, 0.0009, size, spread), "");
  size.imitated_share = 0.40;
  EXPECT_EQ(gap::withinPartsSpread(fx::Kind::kAirDensity, 0.5, size, spread),
            "not named: changes the thrust by at most 1.5 % on any block (3.2 % there is what healthy rotors and "
            "ESCs differ from the bench's by: 2.5 % thrust, 10 us end points); beyond it on 0 blocks, 3 needed, and "
            "they could imitate 40 % of its shape (at most 35 % to name it)");
}

// A thrust loss and an ESC offset are the parts' own laws: their shape never names them.
TEST_F(PartsSpreadTest, TheSpreadsOwnLawsAreJudgedBySizeAlone) {
  gap::PartsSpread spread;
  spread.max_imitated_share = 1.0;  // names every effect reading a signal
  for (const auto& [kind, value] : {std::pair{fx::Kind::kThrustLoss, 0.015}, std::pair{fx::Kind::kEscOffset, 8.0}}) {
    fx::ModelEffects fitted;
    fitted.setParameter(kind, value);
    const gap::EffectSize size = gap::effectSizeAgainstParts(views_, all_, fitted, kind, spread);
    EXPECT_EQ(size.imitated_share, 1.0);
    EXPECT_NE(gap::withinPartsSpread(kind, value, size, spread), "") << fx::describe(kind).name;
  }
  // Beyond the thrust spread a constant loss is only partly imitated, yet still judged by size.
  fx::ModelEffects large;
  large.setParameter(fx::Kind::kThrustLoss, 0.10);
  EXPECT_EQ(gap::effectSizeAgainstParts(views_, all_, large, fx::Kind::kThrustLoss, spread).imitated_share, 1.0);
}

TEST(PartsSpread, RefusesAValueOutsideItsRange) {
  gap::PartsSpread spread;
  spread.thrust_fraction = -0.01;
  try {
    spread.validate();
    FAIL() << "a negative spread was accepted";
  } catch (const pe::FieldError& e) {
    EXPECT_EQ(e.field(), "parts_thrust_spread");
  }
  spread = gap::PartsSpread();
  spread.esc_end_point_us = std::nan("");
  EXPECT_THROW(spread.validate(), pe::FieldError);
  spread = gap::PartsSpread();
  spread.max_imitated_share = 1.5;
  try {
    spread.validate();
    FAIL() << "a share above 1 was accepted";
  } catch (const pe::FieldError& e) {
    EXPECT_EQ(e.field(), "parts_max_imitated_share");
  }
  EXPECT_NO_THROW(gap::PartsSpread().validate());
}

}  // namespace
