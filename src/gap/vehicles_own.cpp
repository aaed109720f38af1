// The vehicle's own effect (the day's air, its motors' warming, parts within their spread): why a
// candidate is one, whether it is modelled before the rounds name anything, and what of it joins the
// correction once they have (Diagnoser::selectEffects).
#include <algorithm>

#include "diagnoser.h"
#include "propulsion_estimator/gap/parts_spread.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

// Why `kind`, fitted with `kinds` (`fit`, its change against the parts' `size`), is the vehicle's
// own rather than a finding: within the parts' spread, or no change from the healthy flights; ""
// when it is neither.
std::string Diagnoser::vehiclesOwn(Kind kind, const std::vector<Kind>& kinds, const EffectFit& fit,
                                   const EffectSize& size) const {
  const double parameter = *fit.effects.parameter(kind);
  // With the effect on the vehicle's healthy flights, their fit may stand in for the parts' spread.
  const bool by_reference =
      judgedByReferenceAlone(kind, config_.reference_effects, betweenFlightShare(effects::requiredSignal(kind)));
  const std::string within_parts = by_reference ? "" : withinPartsSpread(kind, parameter, size, config_.parts_spread);
  if (!within_parts.empty()) return within_parts;
  return notAChange(kind, parameter, flightsHalfWidth(kinds, fit.ci_half.back()),
                    signalMedian(all_, effects::requiredSignal(kind)), config_.reference_effects);
}

// Whether `candidate`, fitted on top of the vehicle's own `own`, is the vehicle's own as well.
bool Diagnoser::ownOnTopOf(Kind own, Kind candidate) const {
  std::vector<Kind> kinds = working_;
  kinds.push_back(own);
  kinds.push_back(candidate);
  const EffectFit fit = fitEffects(views_, all_, kinds, references());
  return !vehiclesOwn(candidate, kinds, fit,
                      effectSizeAgainstParts(views_, all_, fit.effects, candidate, config_.parts_spread))
              .empty();
}

bool Diagnoser::passesOnTopOf(const OwnCandidate& own, Kind candidate) const {
  std::vector<Kind> kinds = working_;
  kinds.push_back(own.kind);
  kinds.push_back(candidate);
  const HeldOutPrediction with = predictHeldOut(kinds);
  return improvesEnough(own.prediction, with, improvementPValue(own.prediction, with, candidate), candidate);
}

void Diagnoser::declineForTheVehiclesOwn(Kind candidate, Kind own, std::size_t first_step,
                                         std::map<Kind, EffectResult>* results) {
  const std::string verdict =
      "passes every test, but " + std::string(effects::kindName(own)) +
      ", the vehicle's own, lowers the joint held-out error more (" +
      formatPrintf("%.2f", (*results)[own].joint_rmse_pct) + " % against " +
      formatPrintf("%.2f", (*results)[candidate].joint_rmse_pct) + " %) and, modelled, leaves it nothing significant: not named";
  (*results)[candidate].reason = verdict;
  for (std::size_t step = first_step; step < diagnosis_.trace.size(); ++step) {
    if (diagnosis_.trace[step].kind == candidate) diagnosis_.trace[step].verdict = verdict;
  }
}

// Whether a candidate (its held-out prediction `with_candidate`) leaves less of the error within
// flights, each flight's mean taken out, than the vehicle's own effect `own` in its place.
bool Diagnoser::explainsMoreWithinFlights(const HeldOutPrediction& with_candidate, const OwnCandidate& own) const {
  return withinFlightMeanSquare(with_candidate) < withinFlightMeanSquare(own.prediction);
}

// A vehicle's own effect left out of the rounds (selectEffects) joins the correction, unnamed, where
// the held-out joint error falls with it: the day's air still carries what differs between flights
// beside a motor heating named for what it does within them, as when it was modelled first.
HeldOutPrediction Diagnoser::offerToTheCorrection(Kind own, const std::vector<RoundOutcome>& rounds,
                                                  const HeldOutPrediction& current) {
  if (std::find(working_.begin(), working_.end(), own) != working_.end() ||
      static_cast<int>(background_.size()) >= kMaxBackgroundEffects) {
    return current;
  }
  std::vector<Kind> with_own = working_;
  with_own.push_back(own);
  HeldOutPrediction prediction = predictHeldOut(with_own);
  if (!(jointMeanSquare(prediction) < jointMeanSquare(current))) return current;
  background_.push_back(own);
  adopt(rounds);
  return prediction;
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
