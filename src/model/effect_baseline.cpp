#include "propulsion_estimator/model/effect_baseline.h"

#include <cmath>

namespace propulsion_estimator {

EffectBaseline effectBaseline(const ModelMetadata& metadata, const std::optional<MotorReference>& reference) {
  EffectBaseline baseline;
  baseline.air_density_kg_m3 = metadata.benchAirDensity();
  baseline.motor_temperature_c = metadata.bench_air_temperature_c.value_or(kNaN);
  if (reference) {
    if (std::isfinite(reference->air_density_kg_m3)) baseline.air_density_kg_m3 = reference->air_density_kg_m3;
    if (std::isfinite(reference->motor_temperature_c)) baseline.motor_temperature_c = reference->motor_temperature_c;
  }
  return baseline;
}

}  // namespace propulsion_estimator
