#include "propulsion_estimator/sim/physics/battery_family.h"

#include <cmath>
#include <functional>
#include <random>
#include <utility>
#include <vector>

#include "propulsion_estimator/common/cells_in_series.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace sim {
namespace {

constexpr int kTablePoints = 51;
constexpr int kMaxDraws = 50000;
// The states of charge of BatteryFamily::cell_v_at.
constexpr std::array<double, 5> kAnchorSoc{0.1, 0.3, 0.5, 0.7, 0.9};
constexpr double kReferenceK = 298.15;
constexpr double kCelsiusToKelvin = 273.15;

void requireRange(const std::string& field, const Range& range, double lo, double hi) {
  requireWithin("battery_family." + field + "[0]", range.lo, lo, hi);
  requireWithin("battery_family." + field + "[1]", range.hi, range.lo, hi);
}

double draw(std::mt19937& rng, const Range& range) {
  return range.lo + (range.hi - range.lo) * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
}

// The shape's rising function of the state of charge, drawn; normalised to the pack's voltages after.
std::function<double(double)> drawShape(OcvShape shape, std::mt19937& rng) {
  const double slope = draw(rng, {0.3, 0.6});
  switch (shape) {
    case OcvShape::kTwoPlateaus: {
      const double knee = draw(rng, {0.25, 0.5}), width = draw(rng, {0.02, 0.06});
      const double step = draw(rng, {0.08, 0.2}), at = draw(rng, {0.55, 0.75}), step_width = draw(rng, {0.03, 0.08});
      return [=](double s) {
        return slope * s + knee * std::tanh(s / width) + step * 0.5 * (1.0 + std::tanh((s - at) / step_width));
      };
    }
    case OcvShape::kRationalKnee: {
      const double plateau = draw(rng, {0.2, 0.5}), cubic = draw(rng, {0.5, 1.5});
      const double knee = draw(rng, {0.3, 0.6}), width = draw(rng, {0.01, 0.04});
      return [=](double s) { return plateau * s + cubic * std::pow(s - 0.5, 3) + knee * s / (s + width); };
    }
    case OcvShape::kExponentialKnee: break;
  }
  const double knee = draw(rng, {0.3, 0.6}), width = draw(rng, {0.02, 0.06});
  const double top = draw(rng, {0.15, 0.35}), power = draw(rng, {3.0, 6.0});
  return [=](double s) { return slope * s + knee * (1.0 - std::exp(-s / width)) + top * std::pow(s, power); };
}

}  // namespace

const char* ocvShapeName(OcvShape shape) {
  switch (shape) {
    case OcvShape::kTwoPlateaus: return "two_plateaus";
    case OcvShape::kRationalKnee: return "rational_knee";
    case OcvShape::kExponentialKnee: break;
  }
  return "exponential_knee";
}

void BatteryFamily::validate() const {
  requireWithin("battery_family.cells", cells, kMinCellsInSeries, kMaxCellsInSeries);
  requirePositive("battery_family.rated_capacity_ah", rated_capacity_ah, 1000.0, " Ah");
  requireRange("cell_empty_v", cell_empty_v, 2.5, 4.4);
  requireRange("cell_full_v", cell_full_v, cell_empty_v.hi, 4.4);
  for (std::size_t k = 0; k < cell_v_at.size(); ++k) {
    requireRange("cell_v_at[" + std::to_string(k) + "]", cell_v_at[k], cell_empty_v.hi, cell_full_v.lo);
  }
  requireRange("series_ohm_per_cell", series_ohm_per_cell, 1e-6, 0.3);
  requireRange("rc_ohm_per_cell", rc_ohm_per_cell, 1e-6, 0.3);
  requireRange("rc_time_constant_s", rc_time_constant_s, 0.1, 1e4);
  requireWithin("battery_family.second_rc_probability", second_rc_probability, 0.0, 1.0);
  requireRange("rc2_ohm_per_cell", rc2_ohm_per_cell, 1e-6, 0.3);
  requireRange("rc2_time_constant_s", rc2_time_constant_s, 0.1, 1e5);
  requireRange("temperature_c", temperature_c, -20.0, 60.0);
  requireRange("capacity_fade", capacity_fade, 0.0, 0.5);
  requireRange("resistance_growth", resistance_growth, 0.0, 3.0);
  requireWithin("battery_family.arrhenius_k", arrhenius_k, 0.0, 1e4);
  requireWithin("battery_family.cold_capacity_per_c", cold_capacity_per_c, 0.0, 0.05);
}

DrawnBattery drawBattery(const BatteryFamily& family, std::uint32_t seed, std::optional<OcvShape> shape) {
  family.validate();
  std::mt19937 rng(seed);
  DrawnBattery pack;
  pack.shape = shape.value_or(static_cast<OcvShape>(rng() % kOcvShapeCount));
  LipoBatteryParams& p = pack.params;
  p.name = std::string("drawn ") + ocvShapeName(pack.shape) + " pack, seed " + std::to_string(seed);
  p.cells = family.cells;
  // A curve whose middle lies where LiPo cells rest: drawn again until it does.
  for (int attempt = 0; attempt < kMaxDraws; ++attempt) {
    const std::function<double(double)> g = drawShape(pack.shape, rng);
    const double empty_v = draw(rng, family.cell_empty_v), full_v = draw(rng, family.cell_full_v);
    const double g0 = g(0.0), g1 = g(1.0);
    const auto cell_v = [&](double s) { return empty_v + (full_v - empty_v) * (g(s) - g0) / (g1 - g0); };
    const auto within = [](const Range& range, double v) { return v >= range.lo && v <= range.hi; };
    bool rests = true;
    for (std::size_t k = 0; k < kAnchorSoc.size(); ++k) rests = rests && within(family.cell_v_at[k], cell_v(kAnchorSoc[k]));
    if (!rests) continue;
    std::vector<double> soc, volts;
    for (int k = 0; k < kTablePoints; ++k) {
      const double s = static_cast<double>(k) / (kTablePoints - 1);
      soc.push_back(s);
      volts.push_back(cell_v(s));
      if (k > 0 && !(volts[k] > volts[k - 1])) break;  // not rising everywhere: drawn again
    }
    if (static_cast<int>(volts.size()) < kTablePoints || !(volts.back() > volts[kTablePoints - 2])) continue;
    p.ocv_soc = std::move(soc);
    p.ocv_cell_v = std::move(volts);
    break;
  }
  if (p.ocv_soc.empty()) {
    throw FieldError("battery_family.cell_v_at", "no curve of shape " + std::string(ocvShapeName(pack.shape)) +
                                                     " rests within it in " + std::to_string(kMaxDraws) + " draws");
  }
  pack.temperature_c = draw(rng, family.temperature_c);
  pack.capacity_fade = draw(rng, family.capacity_fade);
  pack.resistance_growth = draw(rng, family.resistance_growth);
  const double kelvin = pack.temperature_c + kCelsiusToKelvin;
  const double resistance_scale =
      (1.0 + pack.resistance_growth) * std::exp(family.arrhenius_k * (1.0 / kelvin - 1.0 / kReferenceK));
  const double cold = std::max(0.0, 25.0 - pack.temperature_c) * family.cold_capacity_per_c;
  p.capacity_ah = family.rated_capacity_ah * (1.0 - pack.capacity_fade) * (1.0 - cold);
  p.series_resistance_ohm = family.cells * draw(rng, family.series_ohm_per_cell) * resistance_scale;
  p.rc_resistance_ohm = family.cells * draw(rng, family.rc_ohm_per_cell) * resistance_scale;
  p.rc_capacitance_f = draw(rng, family.rc_time_constant_s) / p.rc_resistance_ohm;
  if (std::uniform_real_distribution<double>(0.0, 1.0)(rng) < family.second_rc_probability) {
    p.rc2_resistance_ohm = family.cells * draw(rng, family.rc2_ohm_per_cell) * resistance_scale;
    p.rc2_capacitance_f = draw(rng, family.rc2_time_constant_s) / p.rc2_resistance_ohm;
  }
  p.validate();
  return pack;
}

std::string DrawnBattery::describe() const {
  const LipoBatteryParams& p = params;
  return std::string(ocvShapeName(shape)) + ", " + formatPrintf("%.0f C", temperature_c) + ", " +
         formatPrintf("%.2f Ah", p.capacity_ah) + " (fade " + formatPrintf("%.1f %%", 100.0 * capacity_fade) +
         "), R0 " + formatPrintf("%.1f", 1000.0 * p.series_resistance_ohm) + " + RC " +
         formatPrintf("%.1f", 1000.0 * p.rc_resistance_ohm) +
         (p.rc2_resistance_ohm > 0.0 ? " + RC2 " + formatPrintf("%.1f", 1000.0 * p.rc2_resistance_ohm) : "") +
         " mOhm, 50 % at " + formatPrintf("%.3f V", p.openCircuitVoltage(0.5) / p.cells);
}

}  // namespace sim
}  // namespace propulsion_estimator
