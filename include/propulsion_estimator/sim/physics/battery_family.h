#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "propulsion_estimator/sim/physics/lipo_battery.h"

namespace propulsion_estimator {
namespace sim {

/// Shapes of a simulated cell's open-circuit curve, each a parametric form of its own (none is the
/// estimator's built-in table): a steep exponential knee at empty under a sloped plateau; two
/// plateaus joined by a step (staged intercalation); a cubic plateau on a rational knee.
enum class OcvShape { kExponentialKnee = 0, kTwoPlateaus, kRationalKnee };
constexpr int kOcvShapeCount = 3;  ///< number of OcvShape values
static_assert(static_cast<int>(OcvShape::kRationalKnee) + 1 == kOcvShapeCount, "kOcvShapeCount");
/// "exponential_knee", "two_plateaus", "rational_knee".
const char* ocvShapeName(OcvShape shape);

/// A [lo, hi] range a parameter is drawn from, uniformly.
struct Range {
  double lo = 0.0;  ///< lowest value
  double hi = 0.0;  ///< highest value
};

/// The family packs are drawn from: lithium-polymer packs that are not ours. Resistances per cell
/// at 25 deg C for a new cell; temperature scales them (Arrhenius) and the capacity available;
/// ageing fades the capacity and grows the resistances. The user of a drawn pack knows only its
/// cells, rated capacity and the cut-off.
struct BatteryFamily {
  int cells = 3;                  ///< in series
  double rated_capacity_ah = 4.0;  ///< Ah; what the pack's label says (the user's figure)
  Range cell_empty_v{3.0, 3.35};   ///< V; open-circuit at 0 % charge
  Range cell_full_v{4.15, 4.22};   ///< V; at 100 %
  /// V; where LiPo cells rest at 10, 30, 50, 70 and 90 % charge (the spread of published
  /// resting-voltage charts of LiCoO2-polymer cells): curves outside are drawn again.
  std::array<Range, 5> cell_v_at{{{3.64, 3.72}, {3.74, 3.80}, {3.80, 3.87}, {3.90, 3.98}, {4.05, 4.14}}};
  Range series_ohm_per_cell{0.002, 0.005};  ///< ohm per cell, new, at 25 deg C
  Range rc_ohm_per_cell{0.001, 0.004};      ///< ohm per cell, the fast RC pair
  Range rc_time_constant_s{10.0, 60.0};     ///< s, the fast RC pair
  double second_rc_probability = 0.5;  ///< share of packs with a slow second RC pair
  Range rc2_ohm_per_cell{0.0005, 0.002};   ///< ohm per cell, the slow RC pair
  Range rc2_time_constant_s{150.0, 600.0};  ///< s, the slow RC pair
  Range temperature_c{10.0, 35.0};          ///< deg C, the pack in flight
  Range capacity_fade{0.0, 0.05};       ///< share of the rated capacity lost with age
  Range resistance_growth{0.0, 0.5};    ///< share the resistances grew with age
  double arrhenius_k = 3000.0;          ///< K; resistance x exp(k (1/T - 1/298.15 K))
  double cold_capacity_per_c = 0.005;   ///< capacity lost per deg C below 25 deg C

  /// Throws FieldError (battery_family.FIELD) for 1..14 cells, a capacity not positive, an empty
  /// or reversed range, voltages outside 2.5..4.4 V, a probability outside 0..1.
  void validate() const;
};

/// One pack drawn from the family, and what it was drawn as (the truth, for reports).
struct DrawnBattery {
  LipoBatteryParams params;                      ///< the pack the simulator flies
  OcvShape shape = OcvShape::kExponentialKnee;  ///< its curve's form
  double temperature_c = 25.0;                   ///< deg C
  double capacity_fade = 0.0;                    ///< share of the rated capacity lost with age
  double resistance_growth = 0.0;                ///< share the resistances grew with age

  /// "nernst, 25 C, fade 2 %, R0 15 mOhm, ..." for a report line.
  std::string describe() const;
};

/// Draws the pack of `seed` (a shape of its own unless `shape` is given): the same seed always
/// gives the same pack. Throws FieldError for a bad family.
DrawnBattery drawBattery(const BatteryFamily& family, std::uint32_t seed, std::optional<OcvShape> shape = std::nullopt);

}  // namespace sim
}  // namespace propulsion_estimator
