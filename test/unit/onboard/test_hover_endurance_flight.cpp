// The hover time left on simulated flights, the core estimator fed as the node feeds it: predicted
// 20 s and 60 s after take-off, with its 90 % interval, against the time the simulated vehicle,
// hovering on, takes to reach the loaded cut-off, with packs drawn from the battery family (not our
// curve; the estimator is given only cells, rated capacity and cut-off).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <string>
#include <vector>

#include "capability_flight.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/parallel_for.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/sim/physics/battery_family.h"

using namespace capability_flight;

namespace {

// One prediction of the hover time left and the time the vehicle then hovered until the cut-off.
struct EnduranceCase {
  std::string label;  // seed, pack, payload, start
  double after_s;     // after take-off
  pe::CapabilityReport report;
  double flown_s;

  double error() const { return (report.hover_endurance_s - flown_s) / flown_s; }
  bool inInterval() const { return report.hover_endurance_low_s <= flown_s && flown_s <= report.hover_endurance_high_s; }
};

// One pack's cases and the lines that tell them.
struct PackCases {
  std::vector<EnduranceCase> cases;
  std::string log;
};

// Hovers to the loaded cut-off from 100, 60 and 30 % with pack `seed` drawn from `family` (each seed a
// pack of its own: shape, resistances, temperature, age), empty (odd seeds) and with 0.3 kg: the
// hover time left predicted 20 s and 60 s after take-off against the time the vehicle took. A
// flight that reaches the cut-off within 90 s of take-off is too short to judge a prediction made
// after 60 s and is left out (printed). With `own_curve` the user also gives the pack's own
// open-circuit curve (capability/battery/ocv_table: the drawn pack's table); with
// `temperature_known` the battery messages carry the pack's temperature.
PackCases flyFamilyPack(std::uint32_t seed, bool own_curve, const pe::sim::BatteryFamily& family, bool temperature_known) {
  PackCases out;
  const pe::sim::DrawnBattery drawn = pe::sim::drawBattery(family, seed);
  pe::sim::SimParams params = thesisParams();
  params.battery = drawn.params;
  for (double initial_soc : {1.0, 0.6, 0.3}) {
    const double payload_kg = seed % 2 ? 0.0 : 0.3;
    pe::CapabilityConfig user = userPack();
    if (own_curve) {
      user.ocv_table_soc = drawn.params.ocv_soc;
      user.ocv_table_cell_v = drawn.params.ocv_cell_v;
    }
    CapabilitySink sink(f450(), user, thesisModel(), {20.0, 60.0});
    if (temperature_known) sink.pack_temperature_c = drawn.temperature_c;
    fly(profile(payload_kg, 3000.0, initial_soc, "[0.0, 0.0, 0.0]", "", 2.0, avionicsA(seed)), &sink, {}, params);
    const std::string label = "seed " + std::to_string(seed) + " " + drawn.describe() + ", payload " +
                              std::to_string(payload_kg).substr(0, 3) + " kg, from " +
                              std::to_string(static_cast<int>(100.0 * initial_soc)) + " %";
    if (!sink.cutoff_s || !sink.predictions[0] || !sink.predictions[1]) {
      ADD_FAILURE() << label << ": no cut-off or no prediction";
      continue;
    }
    if (*sink.cutoff_s < *sink.takeoff_s + 90.0) {
      appendf(&out.log, "%s: the cut-off %.0f s after take-off, not judged\n", label.c_str(), *sink.cutoff_s - *sink.takeoff_s);
      continue;
    }
    for (std::size_t k = 0; k < 2; ++k) {
      const CapabilitySink::Prediction& p = *sink.predictions[k];
      out.cases.push_back({label, k == 0 ? 20.0 : 60.0, p.report, *sink.cutoff_s - p.made_s});
      const EnduranceCase& e = out.cases.back();
      const pe::CapabilityReport& c = e.report;
      appendf(&out.log,
              "%s, after %2.0f s: predicted %4.0f s (90 %% %4.0f..%4.0f), flew %4.0f s, error %+5.1f %%%s "
              "(soc %.2f +- %.2f, R %.1f +- %.1f mOhm)\n",
              label.c_str(), e.after_s, c.hover_endurance_s, c.hover_endurance_low_s, c.hover_endurance_high_s,
              e.flown_s, 100.0 * e.error(), e.inInterval() ? "" : " OUTSIDE", c.state_of_charge, c.state_of_charge_std,
              1000.0 * c.internal_resistance_ohm, 1000.0 * c.internal_resistance_std_ohm);
      EXPECT_FALSE(std::isnan(c.hover_endurance_s)) << label << ": " << c.endurance_basis;
    }
  }
  return out;
}

// Every pack of `seeds` flown as flyFamilyPack flies it, the packs in parallel, their lines printed
// in the order of `seeds`.
std::vector<EnduranceCase> flyFamilyPacks(const std::vector<std::uint32_t>& seeds, bool own_curve = false,
                                          const pe::sim::BatteryFamily& family = {}, bool temperature_known = false) {
  std::vector<PackCases> packs(seeds.size());
  pe::parallelFor(seeds.size(), kCores,
                  [&](std::size_t i) { packs[i] = flyFamilyPack(seeds[i], own_curve, family, temperature_known); });
  std::vector<EnduranceCase> cases;
  for (const PackCases& pack : packs) {
    std::fputs(pack.log.c_str(), stdout);
    cases.insert(cases.end(), pack.cases.begin(), pack.cases.end());
  }
  return cases;
}

// The share of `cases` made `after_s` after take-off for which `holds`.
template <typename Predicate>
double shareOf(const std::vector<EnduranceCase>& cases, double after_s, Predicate holds, int* count = nullptr) {
  int n = 0, k = 0;
  for (const EnduranceCase& e : cases) {
    if (e.after_s != after_s) continue;
    ++n;
    k += holds(e);
  }
  if (count) *count = n;
  return n ? static_cast<double>(k) / n : 0.0;
}

// Issue 19's bar (within 15 % after 20 s and 10 % after 60 s, every case) does NOT hold on this
// family (docs/capability.md: the knee of a pack's curve that is not ours, its slow polarisation
// and a cold pack's lost capacity). What is asserted is a regression guard on the median error
// after 60 s, the measured figures printed.
void expectEnduranceOnFamilyPacks(const std::vector<std::uint32_t>& seeds, double median_bound = 0.35,
                                  bool own_curve = false, const pe::sim::BatteryFamily& family = {}) {
  const std::vector<EnduranceCase> cases = flyFamilyPacks(seeds, own_curve, family);
  int n20 = 0, n60 = 0;
  const double within_20 = shareOf(cases, 20.0, [](const EnduranceCase& e) { return std::abs(e.error()) < 0.15; }, &n20);
  const double within_60 = shareOf(cases, 60.0, [](const EnduranceCase& e) { return std::abs(e.error()) < 0.10; }, &n60);
  const double interval_60 = shareOf(cases, 60.0, [](const EnduranceCase& e) { return e.inInterval(); });
  std::printf("within 15 %% after 20 s: %.0f %% of %d; within 10 %% after 60 s: %.0f %% of %d; in the 90 %% interval "
              "after 60 s: %.0f %%\n",
              100.0 * within_20, n20, 100.0 * within_60, n60, 100.0 * interval_60);
  std::vector<double> errors;
  for (const EnduranceCase& e : cases) {
    if (e.after_s == 60.0) errors.push_back(std::abs(e.error()));
  }
  ASSERT_FALSE(errors.empty());
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  EXPECT_LT(errors[errors.size() / 2], median_bound);
}

// Why issue 19's bar (every case within 10 % after 60 s) cannot be met from cells, capacity and the
// cut-off alone. Two packs: one of the family (seed 19: two plateaus, 14 C, 40 mOhm in all, which
// sags it to the cut-off where its curve still bends; picked among 13 drawn packs as one where the
// knee decides, as a counter-example needs only one: seed 8's ratio is about 1.23) and the same
// pack with its curve lowered below 22 % charge, to 5 mV above the family's lowest resting voltage
// at 10 % (the spread of published LiPo charts), a quadratic dip that keeps the curve rising.
// Hovering from 30 %, the first minute never goes below 22 %: every message the node gets is the same, so is any
// estimator's prediction, but the packs reach the loaded cut-off at different times. When the
// longer is more than 1.1 / 0.9 of the shorter, no prediction lies within 10 % of both.
TEST(CapabilityFlight, TwoPacksAlikeAboveTheirKneeGetOnePredictionButNotOneHoverTime) {
  const pe::sim::BatteryFamily family;
  pe::sim::SimParams alike = thesisParams();
  alike.battery = pe::sim::drawBattery(family, 19).params;
  pe::sim::SimParams lower_knee = alike;
  constexpr double kAboveSoc = 0.22;
  const double depth_v = lowerCurveBelow(&lower_knee.battery, kAboveSoc, family);
  ASSERT_GT(depth_v, 0.0);
  // Still a pack of the family's spread at empty and at 10 %.
  const pe::sim::LipoBatteryParams& lowered = lower_knee.battery;
  EXPECT_GE(lowered.ocv_cell_v.front(), family.cell_empty_v.lo);
  EXPECT_GE(lowered.openCircuitVoltage(0.1) / family.cells, family.cell_v_at[0].lo);

  std::array<double, 2> predicted_s{}, flown_s{};
  for (std::size_t k = 0; k < 2; ++k) {
    CapabilitySink sink(f450(), userPack(), thesisModel(), {60.0});
    fly(profile(0.0, 3000.0, 0.3), &sink, {}, k == 0 ? alike : lower_knee);
    ASSERT_TRUE(sink.cutoff_s.has_value());
    ASSERT_TRUE(sink.predictions[0].has_value());
    predicted_s[k] = sink.predictions[0]->report.hover_endurance_s;
    flown_s[k] = *sink.cutoff_s - sink.predictions[0]->made_s;
  }
  std::printf("the curve lowered below %.0f %% by up to %.3f V a cell: predicted %.1f and %.1f s after 60 s, flew %.0f and "
              "%.0f s (ratio %.2f; within 10 %% of both needs at most %.2f)\n",
              100.0 * kAboveSoc, depth_v, predicted_s[0], predicted_s[1], flown_s[0], flown_s[1],
              flown_s[0] / flown_s[1], 1.1 / 0.9);
  EXPECT_EQ(predicted_s[0], predicted_s[1]);
  EXPECT_GT(flown_s[0], 1.1 / 0.9 * flown_s[1]);
}

}  // namespace

// Development seeds chose the estimator's settings; held-out seeds were first run after them; fresh
// seeds were drawn on 2026-11-25 after the settings were fixed and first run then.
const std::vector<std::uint32_t> kDevelopmentSeeds = {1, 2, 3, 4, 5, 6};
const std::vector<std::uint32_t> kHeldOutSeeds = {101, 102, 103, 104, 105, 106};
const std::vector<std::uint32_t> kFreshSeeds = {1551, 2927, 4567, 5106, 6016, 9449};

std::vector<std::uint32_t> allEnduranceSeeds() {
  std::vector<std::uint32_t> seeds = kDevelopmentSeeds;
  seeds.insert(seeds.end(), kHeldOutSeeds.begin(), kHeldOutSeeds.end());
  seeds.insert(seeds.end(), kFreshSeeds.begin(), kFreshSeeds.end());
  return seeds;
}

TEST(CapabilityFlight, HoverEnduranceOnFamilyPacksDevelopmentSeeds) { expectEnduranceOnFamilyPacks(kDevelopmentSeeds); }

TEST(CapabilityFlight, HoverEnduranceOnFamilyPacksHeldOutSeeds) { expectEnduranceOnFamilyPacks(kHeldOutSeeds); }

TEST(CapabilityFlight, HoverEnduranceOnFamilyPacksFreshSeeds) { expectEnduranceOnFamilyPacks(kFreshSeeds); }

// The same packs, the user also giving the pack's own open-circuit curve (capability/battery/
// ocv_table; here the simulator's own table, an ideal measurement): what is left is the
// polarisation a minute shows only in part and a cold or aged pack's lost capacity.
TEST(CapabilityFlight, HoverEnduranceWithThePacksOwnCurve) { expectEnduranceOnFamilyPacks(allEnduranceSeeds(), 0.15, true); }

// Packs of the family at 25 C, new (no fade, no resistance growth), with the fast RC pair only,
// given their own curve: what is left is the polarisation the least squares sees within its memory.
TEST(CapabilityFlight, HoverEnduranceWithTheOwnCurveOfWarmNewPacks) {
  pe::sim::BatteryFamily warm_new;
  warm_new.temperature_c = {25.0, 25.0};
  warm_new.capacity_fade = {0.0, 0.0};
  warm_new.resistance_growth = {0.0, 0.0};
  warm_new.second_rc_probability = 0.0;
  expectEnduranceOnFamilyPacks(allEnduranceSeeds(), 0.06, true, warm_new);
}

namespace {

// The interval's calibration set (development): packs 1..40 of the family (packs 1-6 also chose
// the central figure's settings), the 39 packs drawn on 2026-12-02 that were held out until
// 2026-12-06, and the 40 drawn on 2026-12-06 at a review (docs/capability.md, "The 90 % interval").
std::vector<std::uint32_t> intervalDevelopmentSeeds() {
  std::vector<std::uint32_t> seeds;
  for (std::uint32_t seed = 1; seed <= 40; ++seed) seeds.push_back(seed);
  for (std::uint32_t seed : {67272,  72914,  88398,  101736, 102615, 125930, 182306, 240251, 333205, 340309,
                             341425, 358741, 398125, 419428, 460757, 481506, 504565, 523960, 548411, 552132,
                             555024, 576963, 612108, 614448, 633521, 635817, 693948, 748688, 807895, 832670,
                             860455, 868569, 900689, 906794, 908277, 909784, 939109, 952795, 959195}) {
    seeds.push_back(seed);
  }
  for (std::uint32_t seed : {3358230, 4150845, 2213533, 9102686, 5915025, 6094465, 1872093, 8805309, 7577249, 4705143,
                             1540717, 1065611, 8021891, 3888254, 3748468, 6413010, 6709657, 2009674, 5993584, 5209938,
                             9569679, 9495399, 9544240, 9758419, 6655425, 8474514, 8222992, 4910885, 6771218, 1006740,
                             9511580, 5777583, 8630733, 5277507, 9119935, 9514498, 8289480, 5430237, 3985479, 7011688}) {
    seeds.push_back(seed);
  }
  return seeds;
}

// How many spreads the interval needed below and above the central figure to hold `share` of the
// cases' truths on each side: the `share` quantile of (central - truth) / its spread below, and of
// (truth - central) / its spread above (0 for a truth on the other side).
std::array<double, 2> neededZ(const std::vector<EnduranceCase>& cases, double share, const pe::BatteryEstimatorConfig& pack) {
  std::array<std::vector<double>, 2> z;
  for (const EnduranceCase& e : cases) {
    const pe::CapabilityReport& c = e.report;
    const double below = (c.hover_endurance_s - c.hover_endurance_low_s) / pack.interval_low_z;
    const double above = (c.hover_endurance_high_s - c.hover_endurance_s) / pack.interval_high_z;
    z[0].push_back(std::max(0.0, c.hover_endurance_s - e.flown_s) / below);
    z[1].push_back(std::max(0.0, e.flown_s - c.hover_endurance_s) / above);
  }
  std::array<double, 2> quantile{};
  for (std::size_t side = 0; side < 2; ++side) {
    std::sort(z[side].begin(), z[side].end());
    quantile[side] = z[side][static_cast<std::size_t>(share * (z[side].size() - 1))];
  }
  return quantile;
}

// Held out: 40 packs drawn on 2026-12-06 (random.SystemRandom) after the interval's factors were
// fixed on the development packs (intervalDevelopmentSeeds), first flown then. Every curve shape,
// cold and warm, new and aged packs are among them (asserted).
std::vector<std::uint32_t> intervalHeldOutSeeds() {
  return {1189985, 1193015, 1679792, 1692035, 1910964, 2121869, 2353034, 2528326, 3059647, 3464057,
          3732896, 4159994, 4575437, 5051924, 5069986, 5175229, 5272508, 5473269, 5543985, 5697651,
          5995060, 6493627, 6692463, 6929404, 6950026, 7173459, 7336649, 7415346, 7524526, 8040265,
          8397009, 8675507, 9010469, 9091075, 9136510, 9191231, 9289087, 9417541, 9532752, 9934752};
}

// On each pack's first flight, 60 s after take-off, the 90 % interval holds the time the vehicle
// then hovered in 85-95 % of `cases`.
void expectTheIntervalHolds(const std::vector<EnduranceCase>& cases) {
  int n = 0;
  const double held = shareOf(cases, 60.0, [](const EnduranceCase& e) { return e.inInterval(); }, &n);
  const double below = shareOf(cases, 60.0, [](const EnduranceCase& e) { return e.flown_s < e.report.hover_endurance_low_s; });
  std::printf("after 60 s the 90 %% interval holds the truth in %.1f %% of %d cases (%.1f %% below it, %.1f %% above)\n",
              100.0 * held, n, 100.0 * below, 100.0 * (1.0 - held - below));
  EXPECT_GE(held, 0.85);
  EXPECT_LE(held, 0.95);
}

}  // namespace

// The interval's two factors (capability/battery/interval_low_z, interval_high_z) are what the
// development packs need for 5 % of truths below the interval and 5 % above, after 20 s and 60 s.
TEST(CapabilityFlight, TheEnduranceIntervalIsCalibratedOnTheDevelopmentPacks) {
  const std::vector<EnduranceCase> cases = flyFamilyPacks(intervalDevelopmentSeeds());
  const pe::BatteryEstimatorConfig pack = *userPack().battery();
  const std::array<double, 2> z = neededZ(cases, 0.95, pack);
  int after_60_s = 0;
  const double held_60_s = shareOf(cases, 60.0, [](const EnduranceCase& e) { return e.inInterval(); }, &after_60_s);
  std::printf("%zu cases: the interval needs %.3f spreads below, %.3f above (configured %.3f, %.3f); after 60 s %.1f %% "
              "of %d in it\n",
              cases.size(), z[0], z[1], pack.interval_low_z, pack.interval_high_z, 100.0 * held_60_s, after_60_s);
  EXPECT_NEAR(pack.interval_low_z, z[0], 0.1 * z[0]);
  EXPECT_NEAR(pack.interval_high_z, z[1], 0.1 * z[1]);
}

// The held-out packs (intervalHeldOutSeeds: every curve shape, cold and warm, new and aged among
// them), their temperature unknown to the node.
TEST(CapabilityFlight, TheEnduranceIntervalHoldsTheTruthOnHeldOutPacks) {
  const std::vector<std::uint32_t> seeds = intervalHeldOutSeeds();
  std::array<int, pe::sim::kOcvShapeCount> shapes{};
  int cold = 0, warm = 0, aged = 0, fresh = 0;
  for (std::uint32_t seed : seeds) {
    const pe::sim::DrawnBattery drawn = pe::sim::drawBattery(pe::sim::BatteryFamily{}, seed);
    ++shapes[static_cast<int>(drawn.shape)];
    cold += drawn.temperature_c < 15.0;
    warm += drawn.temperature_c > 25.0;
    aged += drawn.capacity_fade > 0.03 && drawn.resistance_growth > 0.25;
    fresh += drawn.capacity_fade < 0.02 && drawn.resistance_growth < 0.25;
  }
  for (int n : shapes) EXPECT_GE(n, 5);
  EXPECT_GE(std::min({cold, warm, aged, fresh}), 5) << cold << " cold, " << warm << " warm, " << aged << " aged, " << fresh
                                                    << " new";
  expectTheIntervalHolds(flyFamilyPacks(seeds));
}

// The same packs with their temperature reported (BatteryState.temperature): the low end of a warm
// pack's interval no longer allows for a cold one.
TEST(CapabilityFlight, TheEnduranceIntervalHoldsTheTruthOnHeldOutPacksOfKnownTemperature) {
  expectTheIntervalHolds(flyFamilyPacks(intervalHeldOutSeeds(), false, {}, true));
}

// The hover time left every 10 s over one flight of a held-out pack (seed 406777, from 100 %, no
// payload) with its interval, against the time the vehicle then hovered: the truth within the
// interval at nearly every point, the interval narrowing as the charge is drawn. With
// PE_ENDURANCE_CSV set, the series is written there for docs/images (scripts/plot_hover_endurance.py).
TEST(CapabilityFlight, TheHoverTimeLeftOverAFlightWithItsInterval) {
  std::vector<double> after_s;
  for (double t = 20.0; t <= 1500.0; t += 10.0) after_s.push_back(t);
  const pe::sim::DrawnBattery drawn = pe::sim::drawBattery(pe::sim::BatteryFamily{}, 406777);
  pe::sim::SimParams params = thesisParams();
  params.battery = drawn.params;
  CapabilitySink sink(f450(), userPack(), thesisModel(), after_s);
  fly(profile(0.0, 3000.0, 1.0, "[0.0, 0.0, 0.0]", "", 2.0, avionicsA(406777)), &sink, {}, params);
  ASSERT_TRUE(sink.cutoff_s.has_value());
  std::string csv = "after_takeoff_s,predicted_s,low_s,high_s,flown_s\n";
  int points = 0, held = 0;
  double first_width = pe::kNaN, last_width = pe::kNaN;
  for (const std::optional<CapabilitySink::Prediction>& p : sink.predictions) {
    if (!p || p->made_s > *sink.cutoff_s - 30.0) continue;
    const pe::CapabilityReport& c = p->report;
    const double flown_s = *sink.cutoff_s - p->made_s;
    EXPECT_FALSE(std::isnan(c.hover_endurance_s)) << p->made_s - *sink.takeoff_s << " s after take-off: " << c.endurance_basis;
    for (double v : {p->made_s - *sink.takeoff_s, c.hover_endurance_s, c.hover_endurance_low_s, c.hover_endurance_high_s}) {
      csv += pe::formatPrintf("%.1f,", v);
    }
    csv += pe::formatPrintf("%.1f\n", flown_s);
    ++points;
    held += c.hover_endurance_low_s <= flown_s && flown_s <= c.hover_endurance_high_s;
    if (std::isnan(first_width)) first_width = c.hover_endurance_high_s - c.hover_endurance_low_s;
    last_width = c.hover_endurance_high_s - c.hover_endurance_low_s;
  }
  std::printf("%s: the truth within the interval at %d of %d points; width %.0f s after 20 s, %.0f s at the end\n",
              drawn.describe().c_str(), held, points, first_width, last_width);
  ASSERT_GT(points, 40);
  EXPECT_GE(held, 0.8 * points);
  EXPECT_LT(last_width, 0.5 * first_width);
  if (const char* path = std::getenv("PE_ENDURANCE_CSV")) pe::writeTextFile(path, csv);
}
