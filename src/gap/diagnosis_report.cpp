#include "diagnoser.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

std::string groundDrawText(const std::vector<std::string>& measured, const std::vector<std::string>& unmeasured,
                           double stopped_pwm_us) {
  const auto list = [](const std::vector<std::string>& items) {
    std::string text;
    for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
    return text;
  };
  const std::string fitted = "the avionics' draw fitted per held-out unit within 0-" +
                             formatNumber(kMaxAvionicsCurrentA) + " A";
  const std::string readings = "at least " + std::to_string(kMinGroundDrawReadings) +
                               " battery readings with every motor stopped (at or below " +
                               formatNumber(stopped_pwm_us) + " us) for a second";
  if (measured.empty()) {
    return unmeasured.empty() ? "" : "the current view takes out " + fitted + " (no flight has " + readings + ")";
  }
  std::string text = "the current view takes out what the battery gave on the ground with every motor stopped: " +
                     list(measured) + ", and " + fitted + " beyond it";
  if (!unmeasured.empty()) text += "; on " + list(unmeasured) + " (without " + readings + ") all of it is fitted";
  return text;
}

void Diagnoser::reportGap(const BlockView& pwm_view, const std::vector<double>& plain_view) {
  diagnosis_.overall = statsOf(all_, pwm_view);
  diagnosis_.payload_err_pct = payloadErrorPct(blocks_, plain_view);
  for (int f = 0; f < static_cast<int>(flights_.size()); ++f) {
    std::vector<const Block*> mine;
    double mass = 0.0;
    for (const Block* block : all_) {
      if (block->flight != f) continue;
      mine.push_back(block);
      mass += block->mass_kg;
    }
    FlightGap flight{flights_[f].name, statsOf(mine, pwm_view), mine.empty() ? kNaN : mass / mine.size(), {},
                     flights_[f].segments};
    for (const std::string& problem : diagnosis_.problems) {
      if (problem.rfind(flights_[f].name + ":", 0) == 0) flight.problems.push_back(problem);
    }
    diagnosis_.flights.push_back(flight);
  }
  const ThrustViews single(model_, 1);
  for (const BenchLog& log : bench_) diagnosis_.bench.push_back(benchGap(single, log));
}

// The residual over the model's domain: four pulse-width bands by three voltage bands.
Breakdown Diagnoser::operatingRegion(const BlockView& pwm_view) const {
  const ModelDomain& domain = model_.domain();
  Breakdown region;
  region.name = "operating_region";
  std::map<std::string, std::vector<const Block*>> bins;
  const double pwm_step = (domain.pwm_max_us - domain.pwm_min_us) / 4.0;
  const double voltage_step = (domain.voltage_max_v - domain.voltage_min_v) / 3.0;
  for (const Block* block : all_) {
    bool outside = false;
    for (int k = 0; k < motorCount(); ++k) outside |= !domain.contains(block->pwm_us[k], block->voltage_v);
    if (outside) {
      bins["outside the model's domain"].push_back(block);
      continue;
    }
    const int p = std::min(3, static_cast<int>((meanPwm(*block) - domain.pwm_min_us) / pwm_step));
    const int v = std::min(2, static_cast<int>((block->voltage_v - domain.voltage_min_v) / voltage_step));
    const std::string label = formatPrintf("%.0f", domain.pwm_min_us + p * pwm_step) + "-" +
                              formatPrintf("%.0f", domain.pwm_min_us + (p + 1) * pwm_step) + " us x " +
                              formatPrintf("%.2f", domain.voltage_min_v + v * voltage_step) + "-" +
                              formatPrintf("%.2f", domain.voltage_min_v + (v + 1) * voltage_step) + " V";
    bins[label].push_back(block);
  }
  for (const auto& [label, members] : bins) region.bins.push_back({label, statsOf(members, pwm_view)});
  return region;
}

// The residual by phase of flight: near the ground, climb, descent, hover.
Breakdown Diagnoser::phase(const BlockView& pwm_view) const {
  Breakdown phase;
  phase.name = "phase";
  std::map<std::string, std::vector<const Block*>> bins;
  for (const Block* block : all_) {
    const double height = block->signals.value(effects::Signal::kHeight);
    const double speed = block->signals.value(effects::Signal::kVerticalSpeed);
    if (std::isfinite(height) && height < 2.0 * config_.rotor_diameter_m) {
      bins["near the ground"].push_back(block);
    } else if (std::isfinite(speed) && speed > 0.2) {
      bins["climb"].push_back(block);
    } else if (std::isfinite(speed) && speed < -0.2) {
      bins["descent"].push_back(block);
    } else {
      bins["hover"].push_back(block);
    }
  }
  for (const auto& [label, members] : bins) phase.bins.push_back({label, statsOf(members, pwm_view)});
  return phase;
}

// 2. Where it lies: the residual broken down by region, phase, each signal and flight.
void Diagnoser::reportWhere(const BlockView& pwm_view) {
  diagnosis_.where.push_back(operatingRegion(pwm_view));
  diagnosis_.where.push_back(phase(pwm_view));
  const double d = config_.rotor_diameter_m;
  for (effects::Signal signal : effects::allSignals()) {
    const auto value = [signal](const Block& b) { return b.signals.value(signal); };
    // Heights by the rotor's diameter (the ground effect's scale), speeds at fixed steps, the rest by quantiles.
    std::vector<double> edges;
    const char* format = "%.1f";
    switch (signal) {
      case effects::Signal::kHeight:
        edges = {d, 2 * d, 1.0, 2.0, 5.0};
        format = "%.2f";
        break;
      case effects::Signal::kVerticalSpeed:
      case effects::Signal::kAxialSpeed: edges = {-1.0, -0.3, -0.1, 0.1, 0.3, 1.0}; break;
      case effects::Signal::kHorizontalSpeed: edges = {0.5, 1.0, 2.0, 4.0, 8.0}; break;
      case effects::Signal::kAirDensity:
        edges = quantileEdges(all_, value, 3);
        format = "%.3f";
        break;
      default: edges = quantileEdges(all_, value, 4); break;
    }
    diagnosis_.where.push_back(breakdownBy(effects::signalKey(signal), all_, value, edges, pwm_view, format,
                                           effects::sourcesOf(signal, config_.signal_sources)));
  }
  const auto time = [](const Block& b) { return b.flight_time_s; };
  diagnosis_.where.push_back(
      breakdownBy("time_in_flight_s", all_, time, {60.0, 120.0, 300.0, 600.0}, pwm_view, "%.0f", "time"));
  Breakdown by_flight;
  by_flight.name = "flight";
  for (const FlightGap& flight : diagnosis_.flights) {
    if (flight.stats.samples > 0) by_flight.bins.push_back({flight.name, flight.stats});
    // No unmodelled effect halves or doubles the thrust: a gap this large is a mass in other
    // units, a segment on the ground or another vehicle's model, and is said before any effect.
    if (flight.stats.samples > 0 && std::abs(flight.stats.bias_pct) > kImplausibleBiasPct) {
      diagnosis_.problems.push_back(flight.name + ": the model gives " +
                                    formatPrintf("%.1f", 100.0 + flight.stats.bias_pct) +
                                    " % of the thrust its weighed mass needs: is mass_kg in kg (not grams), the vehicle "
                                    "airborne in every segment, and the model this vehicle's?");
    }
  }
  diagnosis_.where.push_back(by_flight);
}

// The moment balance; a motor it points at explains its share of the gap: the effects are sought
// in what remains, so that a weak propeller is not named as an effect of the whole vehicle.
// `selected`: every effect the correction uses.
void Diagnoser::reportEffects(std::map<Kind, EffectResult>* results, const std::vector<Kind>& selected) {
  for (Kind kind : effects::kAllKinds) {
    EffectResult& result = (*results)[kind];
    if (result.testable && std::find(selected.begin(), selected.end(), kind) == selected.end() &&
        result.heldout_rmse_pct == 0.0) {
      // Untried in a round (selection stopped before): fit it alone for the report.
      const EffectFit fit = fitEffects(views_, all_, {kind}, references());
      result.parameter = *fit.effects.parameter(kind);
      result.ci_low = result.parameter - fit.ci_half.back();
      result.ci_high = result.parameter + fit.ci_half.back();
    }
    diagnosis_.effects.push_back(result);
  }
  // The selected effects and the ambiguous groups' leaders, fitted together.
  const EffectFit final_fit = fitEffects(views_, all_, selected, references());
  diagnosis_.fitted = final_fit.effects;
  for (std::size_t k = 0; k < selected.size(); ++k) {
    for (EffectResult& result : diagnosis_.effects) {
      if (result.kind != selected[k]) continue;
      result.parameter = *final_fit.effects.parameter(selected[k]);
      result.ci_low = result.parameter - final_fit.ci_half[k];
      result.ci_high = result.parameter + final_fit.ci_half[k];
    }
  }
}

// 4. How far it shrinks, on held-out flights.
void Diagnoser::reportHeldOut(const HeldOutPrediction& before, const HeldOutPrediction& after) {
  const auto held_stats = [](const HeldOutPrediction& prediction, double* rmse, double* bias) {
    double sum = 0.0, sum2 = 0.0;
    for (double r : prediction.pwm) {
      sum += r;
      sum2 += r * r;
    }
    *rmse = 100.0 * std::sqrt(sum2 / prediction.pwm.size());
    *bias = 100.0 * sum / prediction.pwm.size();
  };
  held_stats(before, &diagnosis_.heldout.before_rmse_pct, &diagnosis_.heldout.before_bias_pct);
  held_stats(after, &diagnosis_.heldout.after_rmse_pct, &diagnosis_.heldout.after_bias_pct);
  diagnosis_.heldout.before_payload_err_pct = payloadErrorPct(blocks_, before.view_n);
  diagnosis_.heldout.after_payload_err_pct = payloadErrorPct(blocks_, after.view_n);
}

// With a rotor lag modelled: the bounds transient blocks were used within, and how many were.
std::string Diagnoser::dynamicBlocks() const {
  if (!(diagnosis_.rotor_time_constant_s > 0.0)) return "";
  return "; with the rotor lag modelled, also " + std::to_string(diagnosis_.dynamic_blocks) +
         " transient blocks within " + formatNumber(config_.dynamic_max_pwm_change_us) + " us and " +
         formatNumber(config_.dynamic_max_accel_m_s2) + " m/s^2";
}

// When the selection ran on some blocks alone: which, and why.
std::string Diagnoser::selectionBlocks() const {
  const std::vector<bool> mask = selectionMask();
  if (mask.empty()) return "";
  const bool transient_out = std::find(steady_.begin(), steady_.end(), false) != steady_.end();
  const bool outside_out = mask != steady_;
  std::string why;
  if (transient_out) {
    why = "a transient block's error also carries what the lag model leaves over, which a mean-shifting effect "
          "would soak up";
  }
  if (outside_out) {
    why += std::string(why.empty() ? "" : "; ") + "outside the model's domain its value is what `outside: " +
           outsideDomainName(model_.domain().outside) + "` gives where the bench measured nothing, which no effect's law "
           "describes";
  }
  return ", on the " + std::to_string(std::count(mask.begin(), mask.end(), true)) +
         (transient_out ? " steady blocks" : " blocks") + (outside_out ? " inside the model's domain" : "") +
         " alone (" + why + "); what they chose is fitted and scored on all " + std::to_string(diagnosis_.blocks);
}

std::string Diagnoser::rpmView() const {
  if (!config_.rpm_view) return "the RPM view left out (--no-rpm-view)";
  if (diagnosis_.rpm_view_blocks == 0) {
    return views_.hasRpmThrust() ? "no RPM view: no block has every motor's speed from ESC telemetry"
                                 : "no RPM view: the model has no thrust_from_rpm (fit_surfaces writes it from a bench "
                                   "log's rpm column)";
  }
  return "the RPM view, each rotor's measured speed through thrust_from_rpm on " +
         std::to_string(diagnosis_.rpm_view_blocks) + " blocks, weighted likewise, here " +
         formatPrintf("%.3g", diagnosis_.rpm_view_weight);
}

std::string Diagnoser::regionalThresholds(const std::map<Kind, double>& thresholds) {
  std::string text;
  for (const auto& [kind, points] : thresholds) {
    text += (text.empty() ? "" : ", ") + std::string(effects::kindName(kind)) + " " + formatPrintf("%.3f", points) + " %";
  }
  return text.empty() ? "none" : text;
}

std::string Diagnoser::method() const {
  return "Quasi-steady " + formatNumber(config_.block_s) + " s blocks only (collective PWM changing by at most " +
         formatNumber(config_.max_pwm_change_us) + " us within the block, vertical acceleration at most " +
         formatNumber(config_.max_accel_m_s2) + " m/s^2" + dynamicBlocks() + "): " + std::to_string(diagnosis_.blocks) +
         " used, " + std::to_string(diagnosis_.transient_blocks) + " transient left out; " + diagnosis_.rotor_lag +
         (diagnosis_.ground_draw.empty() ? std::string() : "; " + diagnosis_.ground_draw) + ". Forward selection over " +
         std::to_string(units_) + " held-out " + unit_name_ + "s (each fitted on the others)" + selectionBlocks() +
         ". An effect is added when the held-out RMSE of the PWM view (or of the RPM view, where there is one) falls "
         "by more than " + formatPrintf("%.3f", config_.min_improvement_pct) + " % of the truth and its mean square by " +
         formatPrintf("%.0f", 100.0 * (1.0 - config_.max_mean_square_ratio)) +
         " % (more than a mismatch of model family alone gives on null flights; an effect whose law acts on some "
         "blocks only, also on those blocks by more than that mismatch gives there: " +
         regionalThresholds(config_.min_regional_improvement_pct) + "), the joint error of the views "
         "(the current view weighted by the PWM view's block-to-block noise variance over its own, here " +
         formatPrintf("%.3g", diagnosis_.current_view_weight) + "; " + rpmView() + ") falls, a sign-flip permutation "
         "test over " + formatPrintf("%.0f", config_.group_s) + " s stretches (" +
         std::to_string(config_.permutations) + " permutations) gives p < " + formatNumber(config_.significance) +
         ", and the fitted parameter lies inside its plausible range with a 95 % interval excluding "
         "no effect; at most " + std::to_string(config_.max_effects) +
         " effects. After an earlier effect or a suspect motor's factor, an effect is named only where it changes "
         "the thrust beyond healthy parts' spread on " + std::to_string(kMinBlocksBeyondParts) +
         " blocks or more, or where its law acts its held-out error falls by more than an earlier law leaves "
         "there (" + regionalThresholds(config_.min_later_regional_improvement_pct) +
         "). When another candidate also passes every test and the leader's lower held-out error over it "
         "is not significant (sign-flip p >= " + formatNumber(config_.ambiguity_p) +
         "), the round's effects are reported ambiguous, not selected; the correction uses the leader. Once no "
         "round adds one, each round is chosen again with the other rounds' effects in (dropped when none passes), "
         "until nothing changes. The nested "
         "hold-out runs all of this again on the flights outside each of " +
         std::to_string(std::min(units_, config_.nested_folds)) + " outer folds and scores that fold.";
}

Diagnoser::PlainViews Diagnoser::plainViews(const effects::ModelEffects& plain) const {
  PlainViews views;
  for (const Block& block : blocks_) {
    views.pwm.push_back(views_.pwmView(block, plain));
    views.current.push_back(views_.currentView(block, plain));
    views.rpm.push_back(views_.rpmView(block, plain));
  }
  return views;
}

// Every block with its signals and the views, for the figures.
void Diagnoser::collectSamples(const PlainViews& plain) {
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const Block& block = blocks_[i];
    GapSample sample;
    sample.flight = block.flight;
    sample.time_s = block.time_s;
    sample.truth_n = block.truth_n;
    sample.model_n = plain.pwm[i];
    sample.current_view_n = plain.current[i];
    sample.rpm_view_n = plain.rpm[i];
    sample.corrected_n = views_.pwmView(block, diagnosis_.fitted);
    sample.pwm_us = meanPwm(block);
    sample.voltage_v = block.voltage_v;
    sample.current_a = block.signals.value(effects::Signal::kBatteryCurrent);
    sample.signals = block.signals;
    sample.flight_time_s = block.flight_time_s;
    sample.hover = block.hover;
    diagnosis_.samples.push_back(sample);
  }
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
