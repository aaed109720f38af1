// Whether a later round's effect is there, or only takes up what an earlier round's effect's law
// leaves over (issue 33 point 5). No correction's law is exactly the truth's: a supply path whose
// resistance rises with the current, a thrust loss that follows each rotor's loading, ESCs each
// with its own gain leave a residual after the first correction, and a second effect that reads a
// signal varying from flight to flight (the motors' temperature, the day's air) takes it up as
// well as a real one would, with a shape no part gives. On the family's development seed 5151 such
// leftovers named by their shape moved the thrust by 0.7-2.2 % (the parts' spread 2.8-3.2 %), those
// named by their size (2.7-3.0 %) were read from the day's air the healthy flights also flew in,
// and the real second effect there (a translational lift) moved it by 17-30 %. So a later
// round names an effect only
//  - by its size: beyond what healthy parts could give (the shape alone, which names a small
//    first effect, does not name a later one), or, for an effect judged where its law acts, by
//    its fall there beyond what an earlier law leaves there (min_later_regional_improvement_pct,
//    whose calibration its header gives: 2.6 times the first round's floor there);
//  - not read from a signal that changes mostly between flights and stays where the healthy
//    flights read it;
//  - when it beats the earlier effects with their strength free to differ between light and heavy
//    loads (each held-out flight's blocks below and above the training flights' median command,
//    current, thrust, flight time or voltage, whichever explains most), by the selection's test.
// A suspect motor's factor is such an earlier law too, from the first round on: one factor on its
// modelled thrust, where a chipped blade also turns less drag torque, so that the motor speeds up
// and its thrust lost changes with the operating point as the battery drains and the motors warm.
// An effect beside it is named only by its size, or a ground effect by its fall near the ground
// (the flexible law above frees effects, not a motor's factor); one beside a rotor lacking below
// the suspect's threshold whose factor alone lowers the error as a name needs (lacking_motor.cpp)
// only by its size: that factor is not in the views the fall near the ground is read on.
#include "diagnoser.h"
#include "propulsion_estimator/common/name_list.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

const FlexibleLaw& Diagnoser::flexibleLaw(const std::vector<Kind>& kinds) {
  const auto known = flexible_laws_.find(kinds);
  if (known != flexible_laws_.end()) return known->second;
  const std::vector<std::pair<const char*, LoadOf>> loads{
      {"collective command", [this](const Block& block) { return meanPwm(block); }},
      {"current", [](const Block& block) { return std::isfinite(block.current_a) ? block.current_a : 0.0; }},
      {"thrust", [](const Block& block) { return block.truth_n; }},
      {"flight time", [](const Block& block) { return block.flight_time_s; }},
      {"voltage", [](const Block& block) { return block.voltage_v; }}};
  FlexibleLaw best;
  best.mean_square = kNaN;
  for (const auto& load : loads) {
    HeldOutPrediction prediction = predictHeldOutByLoad(kinds, load.second);
    const double mean_square = jointMeanSquare(prediction);
    if (!(mean_square >= best.mean_square)) best = {std::move(prediction), mean_square, load.first};
  }
  return flexible_laws_[kinds] = std::move(best);
}

// A signal that changes mostly between flights (the day's air) gives the fit one value per flight:
// with a few flights of different payloads, what an earlier effect's law leaves on each flight
// follows it as closely as a real effect would. Where the vehicle's healthy flights flew in the
// same range of it (widened by the larger of its width and these flights' own), nothing tells the
// two apart.
std::string Diagnoser::readBetweenFlightsAsBefore(Kind kind) const {
  const effects::Signal signal = effects::requiredSignal(kind);
  const auto healthy = config_.reference_effects.find(kind);
  if (signal == effects::Signal::kNone || healthy == config_.reference_effects.end() ||
      !std::isfinite(healthy->second.signal_low) || !readBetweenFlights(kind)) {
    return "";
  }
  const double median = signalMedian(all_, signal);
  double lowest = median, highest = median;
  for (const Block* block : all_) {
    const double value = block->signals.value(signal);
    if (!std::isfinite(value)) continue;
    lowest = std::min(lowest, value);
    highest = std::max(highest, value);
  }
  // Three healthy flights span a narrow range of the day's air: the day-to-day spread these
  // flights show themselves is as ordinary, and a site far from home lies beyond both.
  const double low = healthy->second.signal_low, high = healthy->second.signal_high;
  const double width = std::max(high - low, highest - lowest);
  if (median < low - width || median > high + width) return "";
  return "its signal changes mostly between flights and stays where the vehicle's healthy flights read it (median " +
         formatPrintf("%.4g", median) + " against " + formatPrintf("%.4g", low) + ".." + formatPrintf("%.4g", high) +
         " there): with one value per flight it takes up what the earlier law leaves on each flight as well";
}

std::string Diagnoser::leftOverOfLaw(Kind kind, const std::vector<Kind>& earlier_kinds, const EffectSize& size,
                                     const RegionalError& regional, const HeldOutPrediction& with, double ms) {
  const std::string motor_law = hasSuspect() ? "the suspect motor's factor" : lackingMotorLaw();
  if (earlier_kinds.empty() && motor_law.empty()) return "";
  std::vector<std::string> effect_names;
  for (Kind first : earlier_kinds) effect_names.push_back(effects::kindName(first));
  std::vector<std::string> names = effect_names;
  if (!motor_law.empty()) names.push_back(motor_law);
  const std::string earlier = nameList(names, 4);
  // A lacking rotor's factor is not in the views the regional error was read on: beside it alone
  // the fall near the ground is not what that law leaves there, and was not calibrated.
  const std::map<Kind, double> none;
  const std::map<Kind, double>& later =
      earlier_kinds.empty() && !hasSuspect() ? none : config_.min_later_regional_improvement_pct;
  if (size.blocks_beyond < kMinBlocksBeyondParts && !fallsWhereItActs(kind, regional, later)) {
    return "not named: after " + earlier + ", an effect must move the thrust beyond healthy parts' spread (" +
           formatPrintf("%.1f", size.largest_change_pct) + " % at most here against " +
           formatPrintf("%.1f", size.parts_change_pct) + " %, beyond it on " + std::to_string(size.blocks_beyond) +
           " blocks, " + std::to_string(kMinBlocksBeyondParts) + " needed)" + laterRegionalClause(kind, regional, later) +
           ": a shape alone is what a mis-shaped law of " + earlier + " leaves over as well";
  }
  if (const std::string per_flight = readBetweenFlightsAsBefore(kind); !per_flight.empty()) {
    return "not named: after " + earlier + ", " + per_flight;
  }
  if (earlier_kinds.empty()) return "";
  const std::string effects_before = nameList(effect_names, 3);
  const FlexibleLaw& flexible = flexibleLaw(earlier_kinds);
  const double p = signFlipPValue(groupImprovements(flexible.prediction, with), config_.permutations,
                                  config_.seed + 7919u + static_cast<unsigned>(kind));  // a stream of its own
  if (ms < flexible.mean_square && p < config_.significance) return "";
  return "not taken: no better than " + effects_before + " with a strength free to differ with the " + flexible.load +
         " (joint held-out error " + formatPrintf("%.2f", 100.0 * std::sqrt(ms)) + " % against " +
         formatPrintf("%.2f", 100.0 * std::sqrt(flexible.mean_square)) + " %, p = " + formatPrintf("%.3f", p) +
         "): what the law of " + effects_before + " leaves over, not a second effect";
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
