// The effects of a vehicle's healthy flights (fitReferenceEffects) and the test that an effect
// found on other flights is a change from them (notAChange).
#include "propulsion_estimator/gap/reference_effects.h"

#include <cmath>

#include "diagnoser.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/gap/effect_fit.h"

namespace propulsion_estimator {
namespace gap {

std::string notAChange(effects::Kind kind, double value, double ci_half, double signal_median,
                       const ReferenceEffects& reference) {
  const auto found = reference.find(kind);
  if (found == reference.end()) return "";
  const ReferenceEffect& healthy = found->second;
  if (std::isfinite(healthy.signal_low) && std::isfinite(signal_median)) {
    const double width = healthy.signal_high - healthy.signal_low;
    if (signal_median < healthy.signal_low - width || signal_median > healthy.signal_high + width) return "";
  }
  const double change = std::abs(value - healthy.value);
  if (!(change <= std::hypot(ci_half, healthy.ci_half))) return "";
  const std::string both = formatPrintf("%.4g", healthy.value) + " +- " + formatPrintf("%.2g", healthy.ci_half) +
                           " there, " + formatPrintf("%.4g", value) + " +- " + formatPrintf("%.2g", ci_half) + " here";
  // These flights alone would call it a change; only the healthy flights' own looseness holds it
  // back. The user can act on that: the verdict says so rather than vouching for the vehicle.
  if (change > ci_half && healthy.ci_half > ci_half) {
    return "not named: not shown to be a change from the vehicle's healthy flights (" + both +
           "): these flights alone would call it one, but the healthy flights pin it too loosely; more of them, "
           "or more of its signal on them, would decide";
  }
  return "not named: no change from the vehicle's healthy flights (" + both + "): the vehicle's own, not what changed";
}

// The parts' spread stands in for a reference: without one, healthy rotors and ESCs that differ
// from the bench's can imitate an effect. A vehicle's own healthy flights carry its own parts, and
// their fit of the effect holds whatever those parts imitate, so a change from it is not the
// parts' doing. Not the battery current: it follows the thrust, and what the parts imitate of it
// moves with each flight's payload (on the family's development seeds it named a supply
// resistance on a null and a centre-of-gravity case); not a signal that changes between flights
// (the day's air): a reference's few flights do not pin it.
bool judgedByReferenceAlone(effects::Kind kind, const ReferenceEffects& reference, double between_flight_share) {
  const effects::Signal signal = effects::requiredSignal(kind);
  return reference.count(kind) && signal != effects::Signal::kNone && signal != effects::Signal::kBatteryCurrent &&
         !(between_flight_share > detail::kMostlyBetweenFlights);
}

namespace detail {

namespace {

// Two-sided 95 % quantiles of Student's t for 1..9 degrees of freedom; beyond, 2.26 and less.
double studentT95(int degrees) {
  static const double table[] = {12.71, 4.30, 3.18, 2.78, 2.57, 2.45, 2.36, 2.31, 2.26};
  return degrees >= 1 && degrees <= 9 ? table[degrees - 1] : 2.0 + 2.6 / degrees;
}

}  // namespace

// The fit's interval counts stretches of blocks as independent, but a flight's blocks also err
// together (its payload's hang, its air, its battery): an effect read from a signal that changes
// mostly between flights (the day's air) is known only as well as a handful of flights tell it.
// Each flight left out in turn (the jackknife), its 95 % half-width. (An effect read within each
// flight, as the ground effect at take-off, keeps the fit's interval: its flights each tell it.)
double Diagnoser::jackknifeHalfWidth(const std::vector<Kind>& kinds) const {
  std::set<int> flights;
  for (const Block& block : blocks_) flights.insert(block.flight);
  const int n = static_cast<int>(flights.size());
  if (n < 3) return 0.0;
  std::vector<double> values;
  for (int left_out : flights) {
    std::vector<const Block*> kept;
    for (const Block* block : all_) {
      if (block->flight != left_out) kept.push_back(block);
    }
    const std::optional<double> value = fitEffects(views_, kept, kinds, references()).effects.parameter(kinds.back());
    if (!value || !std::isfinite(*value)) return 0.0;
    values.push_back(*value);
  }
  double mean = 0.0;
  for (double value : values) mean += value / n;
  double sum = 0.0;
  for (double value : values) sum += (value - mean) * (value - mean);
  return studentT95(n - 1) * std::sqrt((n - 1.0) / n * sum);
}

// The share of `signal`'s variance over the blocks that lies between the flights' means: 1 for
// the day's air, near 0 for the height near the ground at each take-off; NaN without the signal.
double Diagnoser::betweenFlightShare(effects::Signal signal) const {
  if (signal == effects::Signal::kNone) return kNaN;
  std::map<int, std::pair<double, int>> sums;
  double total = 0.0;
  int count = 0;
  for (const Block* block : all_) {
    const double value = block->signals.value(signal);
    if (!std::isfinite(value)) continue;
    sums[block->flight].first += value;
    ++sums[block->flight].second;
    total += value;
    ++count;
  }
  if (count < 2) return kNaN;
  const double mean = total / count;
  double all = 0.0, between = 0.0;
  for (const Block* block : all_) {
    const double value = block->signals.value(signal);
    if (!std::isfinite(value)) continue;
    const auto& flight = sums.at(block->flight);
    const double flight_mean = flight.first / flight.second;
    all += (value - mean) * (value - mean);
    between += (flight_mean - mean) * (flight_mean - mean);
  }
  return all > 0.0 ? between / all : kNaN;
}

// The same holds for these flights' own fit when it is compared with the healthy flights'.
double Diagnoser::flightsHalfWidth(const std::vector<Kind>& kinds, double fit_half) const {
  if (!config_.reference_effects.count(kinds.back()) ||
      !readBetweenFlights(kinds.back())) {
    return fit_half;
  }
  return std::max(fit_half, jackknifeHalfWidth(kinds));
}

// The healthy flights' effects are read on the blocks the selection reads a candidate on (the
// steady ones, selectionMask): a transient block also carries what the lag model leaves over, which
// widened the healthy flights' interval of a ground effect (1.6 times at the median over the
// development cases, up to 2.6), until a change no longer stood out from it. An effect read between
// flights (the day's air) is read on every block as before: its interval is its flights'
// jackknife, and on the steady blocks alone three flights' jackknife narrowed until a null case's
// day's air was called a change (development seed 607560).
ReferenceEffects Diagnoser::fitEachBesideTheAir() {
  config_.validate();
  cut();
  findUnits();
  balanceMotors();
  std::vector<Kind> between, within;
  for (Kind kind : effects::kAllKinds) {
    if (!testability(kind).empty()) continue;
    (readBetweenFlights(kind) ? between : within).push_back(kind);
  }
  ReferenceEffects fitted = fitEach(between);
  const std::vector<bool> mask = selectionMask();
  const ReferenceEffects steady = mask.empty() ? fitEach(within) : Diagnoser(*this, mask, views_).fitEach(within);
  fitted.insert(steady.begin(), steady.end());
  return fitted;
}

ReferenceEffects Diagnoser::fitEach(const std::vector<Kind>& kinds_to_fit) const {
  ReferenceEffects fitted;
  for (Kind kind : kinds_to_fit) {
    // These blocks (the steady ones alone) may not test what all of them do.
    if (!testability(kind).empty()) continue;
    // The day's air is on every flight and the diagnosis models it first, as the vehicle's own:
    // each effect is read on top of it here too, or the motors' warming, which follows the day's
    // temperature, would take up the healthy flights' air and be compared with a warming read
    // beside it.
    std::vector<Kind> kinds = {kind};
    if (kind != Kind::kAirDensity && testability(Kind::kAirDensity).empty()) kinds.insert(kinds.begin(), Kind::kAirDensity);
    const EffectFit fit = fitEffects(views_, all_, kinds, references());
    ReferenceEffect effect;
    effect.value = *fit.effects.parameter(kind);
    effect.ci_half = fit.ci_half.back();
    if (readBetweenFlights(kind)) {
      effect.ci_half = std::max(effect.ci_half, jackknifeHalfWidth(kinds));
    }
    if (!std::isfinite(effect.value) || !std::isfinite(effect.ci_half)) continue;
    const effects::Signal signal = effects::requiredSignal(kind);
    if (signal != effects::Signal::kNone) {
      for (const Block* block : all_) {
        const double read = block->signals.value(signal);
        if (!std::isfinite(read)) continue;
        effect.signal_low = std::isfinite(effect.signal_low) ? std::min(effect.signal_low, read) : read;
        effect.signal_high = std::isfinite(effect.signal_high) ? std::max(effect.signal_high, read) : read;
      }
    }
    fitted[kind] = effect;
  }
  return fitted;
}

}  // namespace detail

ReferenceEffects fitReferenceEffects(const PropulsionModel& model, const Vehicle& vehicle,
                                     const std::vector<Flight>& flights, const DiagnosisConfig& config) {
  return detail::Diagnoser(model, vehicle, flights, config, {}).fitEachBesideTheAir();
}

}  // namespace gap
}  // namespace propulsion_estimator
