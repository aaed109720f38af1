#include "propulsion_estimator/offline/flight_estimate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <vector>

#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/offline/flight_feed.h"
#include "propulsion_estimator/onboard/rate_limiter.h"

namespace propulsion_estimator {
namespace offline {
namespace {

// "10.50-12.60 V": a range with each end in `pattern`.
std::string range(double low, double high, const char* pattern, const char* unit) {
  return formatPrintf(pattern, low) + "-" + formatPrintf(pattern, high) + unit;
}

constexpr int kBlockerCount = static_cast<int>(HoverBlocker::kExpired) + 1;

// Why the hover detector said no, as a user reads it.
const char* blockerText(HoverBlocker blocker) {
  switch (blocker) {
    case HoverBlocker::kNone: return "hovering";
    case HoverBlocker::kWindowFilling: return "too few messages in the hover window (a low RCOut rate or gaps)";
    case HoverBlocker::kLowThrust: return "thrust below hover/min_mass_kg (on the ground or idling)";
    case HoverBlocker::kThrustUnsteady: return "thrust unsteady beyond hover/max_thrust_rel_std";
    case HoverBlocker::kTilted: return "tilted beyond hover/max_tilt_deg";
    case HoverBlocker::kClimbingOrSinking: return "climbing or sinking beyond hover/max_vertical_speed_m_s";
    case HoverBlocker::kAccelerating: return "accelerating beyond hover/max_vertical_accel_m_s2";
    case HoverBlocker::kSignalGap: return "the IMU or velocity went stale within the window";
    case HoverBlocker::kExpired: return "no message within the hover window";
  }
  return "unknown";
}

EstimateSample sampleOf(const EstimatorOutput& out) {
  EstimateSample s;
  s.time_s = out.stamp_s;
  s.voltage_v = out.totals.voltage_v;
  s.thrust_n = out.totals.thrust_n;
  s.current_a = out.totals.current_a;
  s.power_w = out.totals.power_w;
  s.lifted_mass_kg = out.totals.mass_kg;
  s.hovering = out.payload.hovering;
  s.total_mass_kg = out.payload.total_mass_kg;
  s.mass_std_kg = out.payload.mass_std_kg;
  s.payload_kg = out.payload.payload_mass_kg;
  s.motors_out_of_domain = out.totals.motors_out_of_domain;
  s.motor_thrust_n.reserve(out.motors.size());
  for (const MotorOutput& m : out.motors) s.motor_thrust_n.push_back(m.estimate.thrust_n);
  return s;
}

// The log's battery voltage and armed PWM ranges, for the domain warning.
struct LogRanges {
  double voltage_min_v = std::numeric_limits<double>::infinity();
  double voltage_max_v = -std::numeric_limits<double>::infinity();
  double pwm_min_us = std::numeric_limits<double>::infinity();
  double pwm_max_us = -std::numeric_limits<double>::infinity();
  double pwm_median_us = kNaN;  ///< of the motors' mean command while armed
};

LogRanges rangesOf(const FlightStreams& streams, std::size_t motors, double disarmed_pwm_max_us) {
  LogRanges r;
  for (const BatteryReading& b : streams.battery) {
    if (!(b.voltage_v > 0.0) || !std::isfinite(b.voltage_v)) continue;
    r.voltage_min_v = std::min(r.voltage_min_v, b.voltage_v);
    r.voltage_max_v = std::max(r.voltage_max_v, b.voltage_v);
  }
  std::vector<double> means;
  for (const RcOutFrame& f : streams.rc_out) {
    const auto first = f.pwm_us.begin();
    const std::size_t n = std::min<std::size_t>(motors, kMaxMotors);
    const auto last = first + static_cast<std::ptrdiff_t>(n);
    if (*std::min_element(first, last) <= disarmed_pwm_max_us) continue;
    r.pwm_min_us = std::min(r.pwm_min_us, *std::min_element(first, last));
    r.pwm_max_us = std::max(r.pwm_max_us, *std::max_element(first, last));
    means.push_back(std::accumulate(first, last, 0.0) / static_cast<double>(n));
  }
  if (!means.empty()) {
    std::nth_element(means.begin(), means.begin() + static_cast<std::ptrdiff_t>(means.size() / 2), means.end());
    r.pwm_median_us = means[means.size() / 2];
  }
  return r;
}

// Hover episodes as they are found, message by message.
class EpisodeTracker {
 public:
  EpisodeTracker(const CapabilityEstimator& capability, double gap_s) : capability_(capability), gap_s_(gap_s) {}

  void add(const EstimatorOutput& out) {
    if (!out.payload.hovering) return;
    if (open_ && out.stamp_s - last_.end_s > gap_s_) close();
    if (!open_) {
      last_ = HoverEpisode{};
      last_.start_s = out.stamp_s;
      open_ = true;
    }
    last_.end_s = out.stamp_s;
    last_output_ = out;
  }
  // The open episode, judged at its last hover sample.
  void close() {
    if (!open_) return;
    open_ = false;
    const MassEstimate& p = last_output_.payload;
    last_.total_mass_kg = p.total_mass_kg;
    last_.mass_std_kg = p.mass_std_kg;
    last_.payload_kg = p.payload_mass_kg;
    last_.window_s = p.window_s;
    last_.voltage_v = last_output_.totals.voltage_v;
    const CapabilityReport c = capability_.evaluate(last_output_);
    last_.thrust_to_weight = c.thrust_to_weight;
    last_.max_additional_payload_kg = c.max_additional_payload_kg;
    episodes_.push_back(last_);
  }
  std::vector<HoverEpisode> take() {
    close();
    return std::move(episodes_);
  }

 private:
  const CapabilityEstimator& capability_;
  double gap_s_;
  bool open_ = false;
  HoverEpisode last_;
  EstimatorOutput last_output_;
  std::vector<HoverEpisode> episodes_;
};

template <typename T>
void addOnce(std::vector<T>* list, const T& value) {
  if (std::find(list->begin(), list->end(), value) == list->end()) list->push_back(value);
}

// The ESC check's judgement, kept when judged; a verdict other than consistent listed once.
void takeEscCheck(ModelCheckReport report, FlightEstimate* result) {
  if (report.verdict == ModelCheckVerdict::kNotJudged) return;
  if (report.verdict != ModelCheckVerdict::kConsistent) {
    addOnce(&result->esc_flags, std::string(modelCheckVerdictName(report.verdict)) +
                                    (report.flagged_channel != 0
                                         ? " on channel " + std::to_string(report.flagged_channel)
                                         : std::string()));
  }
  result->esc_check = std::move(report);
}

void warnRefusals(const EstimatorCounters& counters, const Estimator& estimator, std::vector<std::string>* warnings) {
  std::vector<std::string> refused;
  for (int r = 1; r < kRejectionCount; ++r) {
    const auto reason = static_cast<Rejection>(r);
    if (reason == Rejection::kDisarmed || reason == Rejection::kBadInput || counters.rejected[r] == 0) continue;
    refused.push_back(std::to_string(counters.rejected[r]) + " " + rejectionName(reason));
  }
  for (input::Scalar scalar : input::kAllScalars) {
    const std::uint64_t count = counters.rejected_inputs[input::index(scalar)];
    if (count > 0) refused.push_back(std::to_string(count) + " " + badInputName(scalar));
  }
  if (refused.empty()) return;
  // The last refusal is worth quoting only when it is one of those counted (not a disarmed motor).
  const RejectionDetail& last = estimator.lastRejection();
  warnings->push_back("inputs refused: " + joined(refused) +
                      (last.reason == Rejection::kDisarmed ? "" : " (the last: " + describe(last) + ")"));
}

void warnDomain(const EstimatorCounters& counters, const ModelDomain& domain, const LogRanges& log,
                std::vector<std::string>* warnings) {
  if (counters.motor_samples_outside_domain == 0) return;
  const double share = 100.0 * static_cast<double>(counters.motor_samples_outside_domain) /
                       static_cast<double>(std::max<std::uint64_t>(counters.motor_samples, 1));
  std::string line = formatPrintf("%.1f", share) + " % of the motor samples lie outside the model's domain" +
                     " (the model covers " + range(domain.pwm_min_us, domain.pwm_max_us, "%.0f", " us") + " at " +
                     range(domain.voltage_min_v, domain.voltage_max_v, "%.2f", " V");
  if (log.voltage_min_v <= log.voltage_max_v) {
    line += "; the log's battery reads " + range(log.voltage_min_v, log.voltage_max_v, "%.2f", " V");
  }
  if (log.pwm_min_us <= log.pwm_max_us) {
    line += ", its motors " + range(log.pwm_min_us, log.pwm_max_us, "%.0f", " us") + " while armed";
  }
  // A bench logged along one discharge diagonal covers a narrow band of that box at each command.
  if (!domain.covered.empty() && !std::isnan(log.pwm_median_us)) {
    const auto [low_v, high_v] = domain.voltageRange(log.pwm_median_us);
    line += "; at the log's median command, " + formatPrintf("%.0f us", log.pwm_median_us) +
            ", the bench covered only " + range(low_v, high_v, "%.2f", " V");
  }
  line += std::string("); outside: ") + outsideDomainName(domain.outside);
  const bool in_box = log.voltage_min_v >= domain.voltage_min_v && log.voltage_max_v <= domain.voltage_max_v;
  if (share > 50.0 && !in_box) line += ": is this the right model for this vehicle?";
  if (share > 50.0 && in_box && !domain.covered.empty()) {
    line += ": the surfaces are held to the bench's band (a bench run at several voltages would cover the flight)";
  }
  warnings->push_back(line);
}

void warnNoHover(const std::array<std::uint64_t, kBlockerCount>& blockers, std::uint64_t accepted,
                 std::vector<std::string>* warnings) {
  if (accepted == 0) {
    warnings->push_back("no RCOut message accepted: nothing estimated (see the refusals; disarmed messages are "
                        "not estimated)");
    return;
  }
  int most = 1;
  for (int b = 1; b < kBlockerCount; ++b) most = blockers[b] > blockers[most] ? b : most;
  const double share = 100.0 * static_cast<double>(blockers[most]) / static_cast<double>(accepted);
  warnings->push_back("no hover found in " + std::to_string(accepted) + " accepted messages: most often " +
                      blockerText(static_cast<HoverBlocker>(most)) + " (" + formatPrintf("%.0f", share) +
                      " % of them)");
}

// The node's configuration of a session, from the options.
OnboardConfig onboardConfig(const EstimateOptions& options) {
  OnboardConfig config;
  config.estimator = options.estimator;
  config.capability = options.capability;
  config.esc_telemetry = options.esc_telemetry;
  return config;
}

}  // namespace

void checkEstimateInputs(const PropulsionModel& model, const Vehicle& vehicle, const EstimateOptions& options) {
  options.validate(vehicle.rotors.size());
  // Made and dropped: its constructor refuses what the session could not run with.
  [[maybe_unused]] const OnboardSession session(model, vehicle, onboardConfig(options));
}

void EstimateOptions::validate(std::size_t rotors) const {
  estimator.validate(rotors);
  capability.validate();
  requireWithin("sample_rate_hz", sample_rate_hz, 0.0, 1000.0, " Hz");
}

FlightEstimate estimateFlight(const PropulsionModel& model, const Vehicle& vehicle, const FlightStreams& streams,
                              const EstimateOptions& options) {
  options.validate(vehicle.rotors.size());
  OnboardSession session(model, vehicle, onboardConfig(options));
  RateLimiter limiter(options.sample_rate_hz);
  EpisodeTracker episodes(session.capabilityEstimator(), options.estimator.payload.episode_gap_s);
  std::array<std::uint64_t, kBlockerCount> blockers{};
  double next_verdict_s = -std::numeric_limits<double>::infinity();
  // Each flagged channel, in the order first flagged: when first and in how many judged windows
  // (a flag early in a flight may be gone by its last window, which the summary shows).
  struct ChannelFlags {
    int channel;
    double first_s;
    int windows;
  };
  std::vector<ChannelFlags> flags;
  int judged_windows = 0;

  FlightEstimate result;
  result.source = streams.source;
  const FlightFeed feed(streams);
  if (!feed.arrivals().empty()) result.duration_s = feed.arrivals().back().time_s - feed.arrivals().front().time_s;
  for (const Arrival& a : feed.arrivals()) {
    if (!feed.feed(a, &session)) continue;
    const EstimatorOutput& out = session.estimator().output();
    ++blockers[static_cast<int>(out.hover.blocker)];
    episodes.add(out);
    if (limiter.admit(out.stamp_s)) result.samples.push_back(sampleOf(out));
    // Judged once a second of the log, as the node's ~capability asks (a verdict costs a fit).
    if (out.stamp_s < next_verdict_s) continue;
    next_verdict_s = out.stamp_s + 1.0;
    const MotorHealthVerdict verdict = session.motorHealth();
    if (verdict.judged) result.motor_health = verdict;
    judged_windows += verdict.judged;
    if (verdict.flagged_channel != 0) {
      auto flag = std::find_if(flags.begin(), flags.end(),
                               [&](const ChannelFlags& f) { return f.channel == verdict.flagged_channel; });
      if (flag == flags.end()) {
        flags.push_back({verdict.flagged_channel, out.stamp_s - feed.arrivals().front().time_s, 0});
        flag = std::prev(flags.end());
      }
      ++flag->windows;
    }
    takeEscCheck(session.modelCheck().report(out.stamp_s), &result);
  }
  if (result.esc_check.verdict == ModelCheckVerdict::kNotJudged) {
    result.esc_check = session.modelCheck().report(session.estimator().output().stamp_s);
  }
  const Estimator& estimator = session.estimator();
  result.hovers = episodes.take();
  result.counters = estimator.counters();
  result.empty_mass_kg = estimator.output().payload.empty_mass_kg;
  result.empty_mass_source = emptyMassSourceName(estimator.output().payload.empty_mass_source);
  if (!result.motor_health.judged) result.motor_health = session.motorHealth();
  const CapabilityReport capability = session.capabilityEstimator().evaluate(estimator.output());
  result.pack_resistance_ohm = capability.internal_resistance_ohm;
  result.pack_resistance_std_ohm = capability.internal_resistance_std_ohm;

  warnRefusals(result.counters, estimator, &result.warnings);
  warnDomain(result.counters, model.domain(),
             rangesOf(streams, vehicle.rotors.size(), options.estimator.disarmed_pwm_max_us), &result.warnings);
  if (result.hovers.empty()) warnNoHover(blockers, result.counters.accepted, &result.warnings);
  const int last = result.motor_health.flagged_channel;
  for (const ChannelFlags& flag : flags) {
    result.flagged_channels.push_back(flag.channel);
    result.warnings.push_back(
        "the motor-health check flagged channel " + std::to_string(flag.channel) + " in " +
        std::to_string(flag.windows) + " of " + std::to_string(judged_windows) + " judged windows, first " +
        formatPrintf("%.0f", flag.first_s) +
        " s into the log (its share of the thrust beyond the healthy spread; diagnose_gap locates it)" +
        (last == flag.channel ? std::string("")
         : last == 0          ? std::string("; the last window: no motor stands out")
                              : "; the last window: channel " + std::to_string(last)));
  }
  for (const std::string& flag : result.esc_flags) {
    result.warnings.push_back("the live ESC check said " + flag + " (ESC telemetry against the model)");
  }
  return result;
}

}  // namespace offline
}  // namespace propulsion_estimator
