// Whether the flights can tell the leading candidate of a round from the others that also pass
// every test: a wrong name is worse than an honest "one of these".
#include "diagnoser.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

namespace {

// The flight that would separate the effects of a group: each one's own signature.
std::string separatingFlight(const std::vector<Kind>& kinds) {
  std::string text = "to tell";
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    text += (k == 0 ? " " : k + 1 == kinds.size() ? " from " : ", ") + std::string(effects::kindName(kinds[k]));
  }
  text += ":";
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    text += (k ? "; " : " ") + std::string(effects::describe(kinds[k]).separating_flight);
  }
  return text;
}

}  // namespace

std::optional<Ambiguity> Diagnoser::ambiguityOf(Kind leader, const std::map<Kind, HeldOutPrediction>& admissible) {
  const HeldOutPrediction& lead = admissible.at(leader);
  const double lead_ms = jointMeanSquare(lead);
  Ambiguity ambiguity;
  ambiguity.kinds.push_back(leader);
  double closest_ms = kNaN;
  for (const auto& [kind, prediction] : admissible) {
    if (kind == leader) continue;
    // Per stretch: how much more the other candidate errs than the leader, on held-out flights.
    const std::vector<double> swap = groupImprovements(prediction, lead);
    const double p = signFlipPValue(swap, config_.permutations, config_.seed + 101u * static_cast<unsigned>(kind));
    if (p < config_.ambiguity_p) continue;
    ambiguity.kinds.push_back(kind);
    const double ms = jointMeanSquare(prediction);
    if (!(ms >= closest_ms)) {
      closest_ms = ms;
      ambiguity.swap_p_value = p;
      ambiguity.swap_loss_pct = 100.0 * (std::sqrt(ms) - std::sqrt(lead_ms));
    }
  }
  if (ambiguity.kinds.size() < 2) return std::nullopt;
  // The runner-up second, then the rest by their held-out error.
  std::sort(ambiguity.kinds.begin() + 1, ambiguity.kinds.end(), [&](Kind a, Kind b) {
    return jointMeanSquare(admissible.at(a)) < jointMeanSquare(admissible.at(b));
  });
  ambiguity.separating_flight = separatingFlight(ambiguity.kinds);
  return ambiguity;
}

void Diagnoser::finishReasons(std::map<Kind, EffectResult>* results) const {
  for (const Ambiguity& ambiguity : diagnosis_.ambiguous) {
    std::string group;
    for (Kind kind : ambiguity.kinds) group += (group.empty() ? "" : " or ") + std::string(effects::kindName(kind));
    for (std::size_t k = 0; k < ambiguity.kinds.size(); ++k) {
      EffectResult& result = (*results)[ambiguity.kinds[k]];
      result.reason = "ambiguous: " + group + " (" +
                      (k == 0 ? "the leader, which the correction uses" : "fits nearly as well") + "; swapping the leader for " +
                      effects::kindName(ambiguity.kinds[1]) + " raises the joint held-out error by only " +
                      formatPrintf("%.3f", ambiguity.swap_loss_pct) + " points, p = " +
                      formatPrintf("%.3f", ambiguity.swap_p_value) + "): not named";
    }
  }
  for (Kind kind : background_) {
    EffectResult& result = (*results)[kind];
    result.reason = "modelled as the vehicle's own, " + result.reason;
  }
  for (auto& [kind, result] : *results) {
    const bool working = std::find(working_.begin(), working_.end(), kind) != working_.end();
    if (result.testable && !working && result.reason == "passes every test") {
      // Passed in the last round the selection ran, which had reached its limit.
      result.reason = "passes every test, but at most " + std::to_string(config_.max_effects) + " effects are taken";
    }
  }
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
