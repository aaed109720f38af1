// A pack flown once before: the hover time left on its second flight from the pack file's record
// of its first (issue 36), on packs of the battery family, against the time the simulated vehicle
// then hovers to the loaded cut-off; and the twins that show why no estimator is within 10 % of
// every pack from 30 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "capability_flight.h"
#include "propulsion_estimator/common/parallel_for.h"
#include "propulsion_estimator/onboard/pack_file.h"
#include "propulsion_estimator/sim/physics/battery_family.h"

using namespace capability_flight;

namespace {

// A pack flown once before: from 100 % it hovers `hover_s` (12 % short of the time to its loaded
// cut-off, the truth's, as a pilot lands on the autopilot's warning), lands and rests 10 s; the
// pack file's record after it. `lowest_soc`, when given, gets the pack's lowest charge in the
// flight (CapabilitySink::lowest_true_soc).
pe::PackRecord learnedFromOneFlight(const pe::sim::SimParams& params, double payload_kg, double hover_s,
                                    double avionics_a, double* lowest_soc = nullptr,
                                    const pe::CapabilityConfig& user = userPack()) {
  CapabilitySink sink(f450(), user, thesisModel());
  fly(profile(payload_kg, hover_s, 1.0, "[0.0, 0.0, 0.0]", "", 12.0, avionics_a), &sink, {}, params);
  EXPECT_TRUE(sink.packFlightFinished());
  if (lowest_soc) *lowest_soc = sink.lowest_true_soc;
  pe::PackRecord fresh;
  fresh.pack_id = "family pack";
  fresh.cells = 3;
  return sink.learnPack(fresh);
}

// The share of a second flight's charge left after 60 s (from `soc_60s` to the cut-off's
// `soc_cutoff`) that lies below `learned_lowest_soc`, the lowest the learning flight crossed: what
// the pack record cannot know but from the chemistry's curve. 0..1; all three are the simulated
// pack's reported percentage, rounded to 1 %.
double unseenShare(double soc_60s, double soc_cutoff, double learned_lowest_soc) {
  if (!(soc_60s > soc_cutoff) || std::isnan(learned_lowest_soc)) return pe::kNaN;
  return std::clamp((std::min(soc_60s, learned_lowest_soc) - soc_cutoff) / (soc_60s - soc_cutoff), 0.0, 1.0);
}

// The charges the second flight starts from (issue 36's).
constexpr std::array<double, 3> kSecondFlightStarts = {1.0, 0.6, 0.3};

// The learning flight hovers this share of the full hover to the cut-off: it lands 12 % of its
// hover short (issue 36 allows 15 %).
constexpr double kLearningHoverShare = 0.88;

// s from the take-off to the loaded cut-off of a hover from full, `user` configured; nullopt when
// it reaches none.
std::optional<double> hoverToCutoffS(const pe::sim::SimParams& params, double payload_kg, double avionics_a,
                                     const pe::CapabilityConfig& user) {
  CapabilitySink sink(f450(), user, thesisModel());
  fly(profile(payload_kg, 3000.0, 1.0, "[0.0, 0.0, 0.0]", "", 2.0, avionics_a), &sink, {}, params);
  if (!sink.cutoff_s) return std::nullopt;
  return *sink.cutoff_s - *sink.takeoff_s;
}

// The pack's second flight from 100, 60 and 30 % (packs `seeds` of the family), its record from
// learnedFromOneFlight given: the hover time left 60 s after take-off within 10 % of the truth in
// at least `share` of the cases. With `own_curve` the user also gives the pack's own curve on both
// flights (ocv_table, the simulator's table: an ideal measurement).
void expectALearnedPackWithin10Percent(const std::vector<std::uint32_t>& seeds, double share, bool own_curve = false) {
  struct PackOutcome {
    int cases = 0;
    int within = 0;
    int in_interval = 0;
    int below_interval = 0;  // the truth below the interval's low end: an optimistic interval
    // By start (100, 60, 30 %): cases, within 10 %, and the sum of unseenShare().
    std::array<int, 3> start_cases{}, start_within{};
    std::array<double, 3> start_unseen{};
    std::string log;
  };
  std::vector<PackOutcome> outcomes(seeds.size());
  pe::parallelFor(seeds.size(), kCores, [&](std::size_t i) {
    PackOutcome& out = outcomes[i];
    const std::uint32_t seed = seeds[i];
    const pe::sim::DrawnBattery drawn = pe::sim::drawBattery(pe::sim::BatteryFamily{}, seed);
    pe::sim::SimParams params = thesisParams();
    params.battery = drawn.params;
    const double payload_kg = seed % 2 ? 0.0 : 0.3;
    const double avionics_a = avionicsA(seed);
    pe::CapabilityConfig given = userPack();
    if (own_curve) {
      given.ocv_table_soc = params.battery.ocv_soc;
      given.ocv_table_cell_v = params.battery.ocv_cell_v;
    }
    const std::optional<double> full_s = hoverToCutoffS(params, payload_kg, avionics_a, given);
    if (!full_s) {
      ADD_FAILURE() << "seed " << seed << ": the full hover reached no cut-off";
      return;
    }
    double learned_lowest_soc = pe::kNaN;
    const pe::PackRecord record =
        learnedFromOneFlight(params, payload_kg, kLearningHoverShare * *full_s, avionics_a, &learned_lowest_soc, given);
    for (std::size_t start = 0; start < kSecondFlightStarts.size(); ++start) {
      const double initial_soc = kSecondFlightStarts[start];
      pe::CapabilityConfig user = given;
      user.pack = record;
      CapabilitySink sink(f450(), user, thesisModel(), {60.0});
      fly(profile(payload_kg, 3000.0, initial_soc, "[0.0, 0.0, 0.0]", "", 2.0, avionics_a), &sink, {}, params);
      if (!sink.cutoff_s) {
        ADD_FAILURE() << "seed " << seed << " from " << initial_soc << ": no cut-off";
        continue;
      }
      if (*sink.cutoff_s < *sink.takeoff_s + 90.0 || !sink.predictions[0]) continue;
      const pe::CapabilityReport& c = sink.predictions[0]->report;
      const double flown_s = *sink.cutoff_s - sink.predictions[0]->made_s;
      const double error = (c.hover_endurance_s - flown_s) / flown_s;
      const double unseen =
          unseenShare(sink.predictions[0]->lowest_true_soc, sink.cutoff_true_soc, learned_lowest_soc);
      appendf(&out.log,
              "seed %u %s, payload %.1f kg, from %.0f %%, learned %d points, %.2f Ah, R %.1f mOhm: predicted %.0f s "
              "(90 %% %.0f..%.0f), flew %.0f s, error %+.1f %%; charge %.2f..%.2f, %.0f %% of it below the learning "
              "flight's %.2f\n",
              seed, drawn.describe().c_str(), payload_kg, 100.0 * initial_soc, static_cast<int>(record.ocv_soc.size()),
              record.capacity_ah.value_or(pe::kNaN),
              1000.0 * (record.resistance_ohm.empty() ? pe::kNaN : record.resistance_ohm.back()), c.hover_endurance_s,
              c.hover_endurance_low_s, c.hover_endurance_high_s, flown_s, 100.0 * error,
              sink.predictions[0]->lowest_true_soc, sink.cutoff_true_soc, 100.0 * unseen, learned_lowest_soc);
      ++out.cases;
      out.within += std::abs(error) < 0.10;
      out.in_interval += c.hover_endurance_low_s <= flown_s && flown_s <= c.hover_endurance_high_s;
      out.below_interval += flown_s < c.hover_endurance_low_s;
      ++out.start_cases[start];
      out.start_within[start] += std::abs(error) < 0.10;
      out.start_unseen[start] += unseen;
    }
  });
  int cases = 0, within = 0, in_interval = 0, below_interval = 0;
  std::array<int, 3> start_cases{}, start_within{};
  std::array<double, 3> start_unseen{};
  for (const PackOutcome& outcome : outcomes) {
    std::fputs(outcome.log.c_str(), stdout);
    cases += outcome.cases;
    within += outcome.within;
    in_interval += outcome.in_interval;
    below_interval += outcome.below_interval;
    for (std::size_t k = 0; k < start_cases.size(); ++k) {
      start_cases[k] += outcome.start_cases[k];
      start_within[k] += outcome.start_within[k];
      start_unseen[k] += outcome.start_unseen[k];
    }
  }
  for (std::size_t k = 0; k < start_cases.size(); ++k) {
    std::printf("from %.0f %%: within 10 %% in %d of %d cases; on average %.0f %% of the charge left after 60 s lies "
                "below the lowest the learning flight crossed\n",
                100.0 * kSecondFlightStarts[k], start_within[k], start_cases[k],
                start_cases[k] ? 100.0 * start_unseen[k] / start_cases[k] : pe::kNaN);
  }
  std::printf("a pack flown once before: within 10 %% after 60 s in %d of %d cases; the truth in the 90 %% interval in "
              "%d, below its low end (the interval optimistic) in %d\n",
              within, cases, in_interval, below_interval);
  ASSERT_GT(cases, 0);
  EXPECT_GE(within, share * cases);
  // What the bar from 30 % asks about (docs/capability.md): most of the charge left after 60 s
  // lies below the lowest the learning flight crossed.
  ASSERT_GT(start_cases[2], 0);
  EXPECT_GT(start_unseen[2] / start_cases[2], 0.5);
  // The interval, calibrated on first flights, stays honest on a learned pack: it may be too wide,
  // but its low end is above the truth in at most 5 % of cases.
  EXPECT_LE(below_interval, 0.05 * cases);
}

// Development for the learned packs: packs 1-20 of the family, which chose how a flight is learned.
std::vector<std::uint32_t> developmentPacks() {
  std::vector<std::uint32_t> seeds;
  for (std::uint32_t seed = 1; seed <= 20; ++seed) seeds.push_back(seed);
  return seeds;
}

// Held out for the learned packs: 20 packs drawn on 2026-12-02 after the learner was fixed on
// packs 1-20, first flown then.
const std::vector<std::uint32_t> kLearnedHeldOutPacks = {65406,  229737, 243417, 257057, 274397, 323679, 444364,
                                                         491976, 499329, 544398, 551762, 565555, 576810, 658139,
                                                         714122, 754525, 788487, 875409, 917716, 957820};

// A learned pack's twin that no estimator tells apart from it on its second flight from 30 %. The
// learning flight lands 12 % of its hover short of the cut-off (issue 36 allows 15 %), so a second
// flight from 30 % ends in charge the first never crossed. The twin is the family pack `seed` with
// its curve lowered (lowerCurveBelow) below both the learning flight's lowest charge and the
// second flight's charge after 60 s, less 0.01 (the charges are read from the percentage, rounded
// to 1 %). Its learning flight, the same hover, also lands within 15 % of its own cut-off. Both
// learning flights give the same pack record to the last bit and both second flights the same
// messages for a minute, so any estimator's prediction is the same (asserted). Returns the pack's
// hover time after 60 s over its twin's; 1 when it has no twin (already at the charts' lowest at
// 10 %, or flown below 11 %); NaN when a flight reached no cut-off or the second's, like
// expectALearnedPackWithin10Percent's, came within 90 s of the take-off.
double learnedAlikeHoverRatio(std::uint32_t seed, bool print) {
  const pe::sim::BatteryFamily family;
  pe::sim::SimParams alike = thesisParams();
  alike.battery = pe::sim::drawBattery(family, seed).params;
  const double payload_kg = seed % 2 ? 0.0 : 0.3, avionics_a = avionicsA(seed);
  const auto learn = [&](const pe::sim::SimParams& params, double hover_s, double* lowest_soc) {
    return learnedFromOneFlight(params, payload_kg, hover_s, avionics_a, lowest_soc);
  };
  const auto toCutoff = [&](const pe::sim::SimParams& params) {
    const std::optional<double> seconds = hoverToCutoffS(params, payload_kg, avionics_a, userPack());
    EXPECT_TRUE(seconds.has_value());
    return seconds.value_or(pe::kNaN);
  };
  const auto secondFlight = [&](const pe::sim::SimParams& params, const pe::PackRecord& record) {
    pe::CapabilityConfig user = userPack();
    user.pack = record;
    CapabilitySink sink(f450(), user, thesisModel(), {60.0});
    fly(profile(payload_kg, 3000.0, 0.3, "[0.0, 0.0, 0.0]", "", 2.0, avionics_a), &sink, {}, params);
    EXPECT_TRUE(sink.cutoff_s && sink.predictions[0]);
    return sink;
  };
  const double hover_s = kLearningHoverShare * toCutoff(alike);
  double learned_lowest_soc = pe::kNaN;
  {
    const CapabilitySink second = secondFlight(alike, learn(alike, hover_s, &learned_lowest_soc));
    if (!second.predictions[0]) return pe::kNaN;
    learned_lowest_soc = std::min(learned_lowest_soc, second.predictions[0]->lowest_true_soc);
  }
  if (!(learned_lowest_soc > 0.11)) return 1.0;
  double above_soc = learned_lowest_soc - 0.01;
  // A point of the table at above_soc, on its line: the curve interpolates linearly, and lowering
  // the points below must leave the curve above as it was, to the last bit.
  std::vector<double>& socs = alike.battery.ocv_soc;
  std::vector<double>& cell_vs = alike.battery.ocv_cell_v;
  const auto at = std::lower_bound(socs.begin(), socs.end(), above_soc - 1e-6);
  if (std::abs(*at - above_soc) < 1e-6) {
    above_soc = *at;
  } else {
    cell_vs.insert(cell_vs.begin() + (at - socs.begin()),
                   alike.battery.openCircuitVoltage(above_soc) / alike.battery.cells);
    socs.insert(at, above_soc);
  }
  const pe::PackRecord record = learn(alike, hover_s, nullptr);
  const CapabilitySink second = secondFlight(alike, record);
  if (!second.cutoff_s || !second.predictions[0] || *second.cutoff_s < *second.takeoff_s + 90.0) return pe::kNaN;

  pe::sim::SimParams lower = alike;
  const double depth_v = lowerCurveBelow(&lower.battery, above_soc, family);
  if (!(depth_v > 0.0)) return 1.0;
  EXPECT_GE(lower.battery.openCircuitVoltage(0.1) / lower.battery.cells, family.cell_v_at[0].lo);
  EXPECT_GE(lower.battery.ocv_cell_v.front(), family.cell_empty_v.lo - 1e-12);
  // The lowered pack's learning flight also lands within 15 % of its own cut-off, before it.
  const double lower_to_cutoff_s = toCutoff(lower);
  EXPECT_GE(hover_s, 0.85 * lower_to_cutoff_s);
  EXPECT_LT(hover_s, lower_to_cutoff_s);
  EXPECT_EQ(pe::packFileText(learn(lower, hover_s, nullptr)), pe::packFileText(record));
  const CapabilitySink lowered = secondFlight(lower, record);
  if (!lowered.predictions[0] || !lowered.cutoff_s) return pe::kNaN;
  EXPECT_EQ(lowered.predictions[0]->report.hover_endurance_s, second.predictions[0]->report.hover_endurance_s);
  const double flown_s = *second.cutoff_s - second.predictions[0]->made_s;
  const double lower_flown_s = *lowered.cutoff_s - lowered.predictions[0]->made_s;
  if (print) {
    std::printf("seed %u: both flights' first minutes down to %.3f; the curve lowered below %.3f by up to "
                "%.3f V a cell: predicted %.1f s for both, flew %.0f and %.0f s (ratio %.3f; within 10 %% of both "
                "needs at most %.3f)\n",
                seed, learned_lowest_soc, above_soc, depth_v,
                second.predictions[0]->report.hover_endurance_s, flown_s, lower_flown_s, flown_s / lower_flown_s,
                1.1 / 0.9);
  }
  return flown_s / lower_flown_s;
}

}  // namespace

// Why issue 36's bar for a learned pack cannot be met from 30 % on every pack: the family pack of
// seed 19 (two plateaus, 14 C) and its twin (learnedAlikeHoverRatio) get one prediction after 60 s
// from one pack record, but hover for times more than 1.1 / 0.9 apart: no prediction lies within
// 10 % of both.
TEST(CapabilityFlight, TwoPacksLearnedAlikeGetOnePredictionFrom30PercentButNotOneHoverTime) {
  EXPECT_GT(learnedAlikeHoverRatio(19, true), 1.1 / 0.9);
}

// How many of the family's packs have such a twin, development packs 1-20 and the held-out packs
// of APackFlownOnceBeforeHeldOutPacks (measured 2026-12-06: 6 of 20 and 3 of 20; ratios printed,
// a pack with no cut-off 90 s after the take-off from 30 % printed as nan). Each such pair costs
// any estimator one case of the two from 30 %. Asserted: at least 5 and 2, as a regression guard.
TEST(CapabilityFlight, LearnedPacksThatHaveATwinFrom30Percent) {
  const std::vector<std::pair<std::vector<std::uint32_t>, int>> sets = {{developmentPacks(), 5}, {kLearnedHeldOutPacks, 2}};
  for (const auto& [seeds, least] : sets) {
    std::vector<double> ratios(seeds.size());
    pe::parallelFor(seeds.size(), kCores, [&](std::size_t i) { ratios[i] = learnedAlikeHoverRatio(seeds[i], false); });
    int twins = 0;
    std::string list;
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      appendf(&list, " %u:%.3f", seeds[i], ratios[i]);
      twins += ratios[i] > 1.1 / 0.9;
    }
    std::printf("packs with a twin no estimator tells apart from 30 %% (hover ratio above %.3f): %d of %zu;%s\n",
                1.1 / 0.9, twins, seeds.size(), list.c_str());
    EXPECT_GE(twins, least);
  }
}

// Development: packs 1-20 chose how a flight is learned (measured 2026-12-02: 43 of 60 within
// 10 % after 60 s; from 100 % 20 of 20, 60 % 19 of 20, 30 % 4 of 20, where on average 12 %, 25 %
// and 75 % of the charge left after 60 s lies below the lowest the learning flight crossed; the same packs unlearned, HoverEnduranceOnFamilyPacks*, about 3 in 10). Issue
// 36's bar, 90 %, does not hold: from 30 % charge the hover left after 60 s is 1-3 minutes; packs
// with a flat stretch read their charge high (a minute's polarisation is not the long hover's the
// learned curve holds), knee packs learn a capacity 7-20 % short (docs/capability.md), and the
// hover's end lies in charge the learning flight never crossed, where a pack's twin may end
// otherwise (LearnedPacksThatHaveATwinFrom30Percent). Asserted: the measured share, as a
// regression guard.
TEST(CapabilityFlight, APackFlownOnceBeforeDevelopmentPacks) {
  expectALearnedPackWithin10Percent(developmentPacks(), 0.71);
}

// Held out: 20 packs drawn on 2026-12-02 after the learner was fixed on packs 1-20, first flown
// then (with each pack's avionics draw since: 39 of 56 within 10 %; from 100 %: 19 of 20, 60 %:
// 14 of 19, 30 %: 6 of 17, where on average 79 % of the charge left after 60 s lies below the
// lowest the learning flight crossed). Asserted: that share, as a regression guard.
TEST(CapabilityFlight, APackFlownOnceBeforeHeldOutPacks) {
  expectALearnedPackWithin10Percent(kLearnedHeldOutPacks, 0.69);
}

// The development packs with their own curve given as well (docs/capability.md): the part of the
// curve the learning flight never crossed is then known, and what is left is the capacity learned
// at a rest 10 s after the landing and the curve learned under load (measured 2026-12-06: 48 of
// 60, from 30 %: 10 of 20). Asserted: that share, as a regression guard.
TEST(CapabilityFlight, APackFlownOnceBeforeWithItsOwnCurveDevelopmentPacks) {
  expectALearnedPackWithin10Percent(developmentPacks(), 0.79, true);
}

// The held-out packs with their own curve given as well (measured 2026-12-06: 38 of 56, from 30 %:
// 6 of 17). Asserted: that share, as a regression guard.
TEST(CapabilityFlight, APackFlownOnceBeforeWithItsOwnCurveHeldOutPacks) {
  expectALearnedPackWithin10Percent(kLearnedHeldOutPacks, 0.67, true);
}
