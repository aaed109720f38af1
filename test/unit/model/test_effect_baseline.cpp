// What the effects' laws read the air and the motors' warmth against: the bench's, or a healthy
// reference's where it holds them, each on its own.
#include <cmath>
#include <optional>

#include <gtest/gtest.h>

#include "propulsion_estimator/model/effect_baseline.h"
#include "propulsion_estimator/model/effect_signals.h"

namespace pe = propulsion_estimator;

namespace {

pe::ModelMetadata benchAt(double temperature_c, double pressure_pa) {
  pe::ModelMetadata metadata;
  metadata.bench_air_temperature_c = temperature_c;
  metadata.bench_air_pressure_pa = pressure_pa;
  return metadata;
}

pe::MotorReference reference(double air_density_kg_m3, double motor_temperature_c) {
  pe::MotorReference r;
  r.air_density_kg_m3 = air_density_kg_m3;
  r.motor_temperature_c = motor_temperature_c;
  return r;
}

}  // namespace

TEST(EffectBaseline, WithoutAReferenceTheBenchsAirAndTemperature) {
  const pe::EffectBaseline b = pe::effectBaseline(benchAt(20.0, 100000.0), std::nullopt);
  EXPECT_DOUBLE_EQ(b.air_density_kg_m3, pe::effects::airDensityKgM3(100000.0, 20.0));
  EXPECT_DOUBLE_EQ(b.motor_temperature_c, 20.0);
}

TEST(EffectBaseline, AReferenceHoldingAirAndWarmthReplacesTheBenchs) {
  const pe::EffectBaseline b = pe::effectBaseline(benchAt(20.0, 100000.0), reference(1.05, 41.5));
  EXPECT_DOUBLE_EQ(b.air_density_kg_m3, 1.05);
  EXPECT_DOUBLE_EQ(b.motor_temperature_c, 41.5);
}

// A reference whose flights gave no motor temperature (or no air) keeps the bench's for that one.
TEST(EffectBaseline, EachMissingFromTheReferenceStaysTheBenchs) {
  const pe::ModelMetadata bench = benchAt(25.0, 95000.0);
  const pe::EffectBaseline air_only = pe::effectBaseline(bench, reference(1.10, pe::kNaN));
  EXPECT_DOUBLE_EQ(air_only.air_density_kg_m3, 1.10);
  EXPECT_DOUBLE_EQ(air_only.motor_temperature_c, 25.0);
  const pe::EffectBaseline warmth_only = pe::effectBaseline(bench, reference(pe::kNaN, 38.0));
  EXPECT_DOUBLE_EQ(warmth_only.air_density_kg_m3, pe::effects::airDensityKgM3(95000.0, 25.0));
  EXPECT_DOUBLE_EQ(warmth_only.motor_temperature_c, 38.0);
}

TEST(EffectBaseline, NeitherKnownIsNotANumber) {
  const pe::EffectBaseline b = pe::effectBaseline(pe::ModelMetadata{}, std::nullopt);
  EXPECT_TRUE(std::isnan(b.air_density_kg_m3));
  EXPECT_TRUE(std::isnan(b.motor_temperature_c));
}
