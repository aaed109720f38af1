// An effect is named only beyond what a healthy vehicle's parts differ from the bench unit by.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "propulsion_estimator/common/field_error.h"
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
  for (gap::Block& block : blocks_) block.signals.battery_current_a = 20.0;
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
  EXPECT_NO_THROW(gap::PartsSpread().validate());
}

}  // namespace
