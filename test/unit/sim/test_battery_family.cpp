// The simulator's battery family: packs that are not ours, drawn per seed (the same seed, the same
// pack), of three curve shapes none of which is the estimator's built-in table, with resistances,
// temperature and age; its refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/onboard/ocv_curve.h"
#include "propulsion_estimator/sim/physics/battery_family.h"

namespace pe = propulsion_estimator;

TEST(BatteryFamily, TheSameSeedDrawsTheSamePack) {
  const pe::sim::BatteryFamily family;
  const pe::sim::DrawnBattery a = pe::sim::drawBattery(family, 42), b = pe::sim::drawBattery(family, 42);
  EXPECT_EQ(a.params.ocv_cell_v, b.params.ocv_cell_v);
  EXPECT_EQ(a.params.series_resistance_ohm, b.params.series_resistance_ohm);
  EXPECT_EQ(a.describe(), b.describe());
  EXPECT_NE(pe::sim::drawBattery(family, 43).params.ocv_cell_v, a.params.ocv_cell_v);
}

TEST(BatteryFamily, PacksOfEveryShapeAreValidAndNotOurCurve) {
  const pe::sim::BatteryFamily family;
  const pe::OcvCurve ours = pe::OcvCurve::lipo();
  std::set<int> shapes;
  for (std::uint32_t seed = 1; seed <= 30; ++seed) {
    const pe::sim::DrawnBattery pack = pe::sim::drawBattery(family, seed);
    shapes.insert(static_cast<int>(pack.shape));
    const pe::sim::LipoBatteryParams& p = pack.params;
    EXPECT_NO_THROW(p.validate()) << pack.describe();
    const double mid = p.openCircuitVoltage(0.5) / p.cells;
    EXPECT_GE(mid, family.cell_v_at[2].lo);
    EXPECT_LE(mid, family.cell_v_at[2].hi);
    EXPECT_LE(p.capacity_ah, family.rated_capacity_ah);
    EXPECT_GT(p.series_resistance_ohm, 0.0);
    // Somewhere the pack's curve lies at least 20 mV off ours.
    double largest = 0.0;
    for (double soc = 0.05; soc < 1.0; soc += 0.05) {
      largest = std::max(largest, std::abs(p.openCircuitVoltage(soc) / p.cells - ours.cellVoltage(soc)));
    }
    EXPECT_GT(largest, 0.02) << pack.describe();
  }
  EXPECT_EQ(shapes.size(), static_cast<std::size_t>(pe::sim::kOcvShapeCount));
}

// Cold raises the resistances (Arrhenius) and lowers the capacity; age does both too.
TEST(BatteryFamily, TemperatureAndAgeActOnResistanceAndCapacity) {
  pe::sim::BatteryFamily family;
  family.temperature_c = {25.0, 25.0};
  family.capacity_fade = {0.0, 0.0};
  family.resistance_growth = {0.0, 0.0};
  const pe::sim::DrawnBattery warm = pe::sim::drawBattery(family, 5);
  family.temperature_c = {0.0, 0.0};
  const pe::sim::DrawnBattery cold = pe::sim::drawBattery(family, 5);
  EXPECT_NEAR(cold.params.series_resistance_ohm / warm.params.series_resistance_ohm,
              std::exp(3000.0 * (1.0 / 273.15 - 1.0 / 298.15)), 1e-9);
  EXPECT_NEAR(cold.params.capacity_ah, 4.0 * (1.0 - 25 * 0.005), 1e-9);
  family.temperature_c = {25.0, 25.0};
  family.capacity_fade = {0.1, 0.1};
  family.resistance_growth = {0.5, 0.5};
  const pe::sim::DrawnBattery aged = pe::sim::drawBattery(family, 5);
  EXPECT_NEAR(aged.params.capacity_ah, 3.6, 1e-9);
  EXPECT_NEAR(aged.params.series_resistance_ohm, 1.5 * warm.params.series_resistance_ohm, 1e-12);
}

TEST(BatteryFamily, RefusesABadFamilyWithOneLine) {
  pe::sim::BatteryFamily family;
  family.cell_full_v = {4.3, 4.2};
  try {
    pe::sim::drawBattery(family, 1);
    FAIL();
  } catch (const pe::FieldError& e) {
    EXPECT_EQ(std::string(e.what()), "battery_family.cell_full_v[1]: 4.2 is outside 4.3..4.4");
  }
  family = {};
  family.second_rc_probability = 2.0;
  EXPECT_THROW(family.validate(), pe::FieldError);
}
