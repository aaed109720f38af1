#include "propulsion_estimator/onboard/health_summary.h"

#include <cmath>
#include <sstream>

#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace {

// As diagnostic_updater's DiagnosticStatusWrapper::add formats a value, so that the node's
// /diagnostics read as they did when it formatted them itself.
template <typename T>
std::string shown(const T& value) {
  std::ostringstream out;
  out << value;
  return out.str();
}
std::string shown(bool value) { return value ? "True" : "False"; }

template <typename T>
void add(HealthStatus* status, const std::string& key, const T& value) {
  status->values.emplace_back(key, shown(value));
}

// What the model did with the samples outside its domain, as the domain warning says it.
const char* treatmentOutsideDomain(OutsideDomain policy) {
  switch (policy) {
    case OutsideDomain::kClamp: return "clamped";
    case OutsideDomain::kExtrapolate: return "extrapolated";
    case OutsideDomain::kReject: return "refused";
  }
  return "refused";
}

double rate(std::uint64_t now, std::uint64_t before, double seconds) {
  return seconds > 0.0 ? static_cast<double>(now - before) / seconds : 0.0;
}

}  // namespace

void HealthConfig::validate() const { requireWithin("domain_warn_fraction", domain_warn_fraction, 0.0, 1.0); }

HealthStatus judgeInputs(const Estimator& estimator, const HealthSnapshot& before, const HealthSnapshot& now,
                         const HealthConfig& config) {
  HealthStatus status;
  const double seconds = now.time_s - before.time_s;
  const char* const names[kNodeInputCount] = {"rc_out rate (Hz)", "battery rate (Hz)", "imu rate (Hz)",
                                              "velocity rate (Hz)"};
  for (int i = 0; i < kNodeInputCount; ++i) {
    add(&status, names[i], rate(now.inputs.received[i], before.inputs.received[i], seconds));
  }
  const int rc_out = static_cast<int>(NodeInput::kRcOut);
  const double age = estimator.batteryAge(now.time_s);
  add(&status, "battery age (s)", age);
  add(&status, "imu messages without orientation", now.inputs.imu_without_orientation);

  const double timeout = estimator.config().battery_timeout_s;
  std::ostringstream message;
  message.precision(3);
  if (std::isinf(age)) {
    status.level = HealthLevel::kError;
    message << "estimates stopped: no valid battery voltage received on " << config.battery_input;
  } else if (age > timeout) {
    status.level = HealthLevel::kError;
    message << "estimates stopped: no battery voltage for " << age << " s (limit " << timeout << " s) on "
            << config.battery_input;
  } else if (now.inputs.received[rc_out] == before.inputs.received[rc_out]) {
    status.level = HealthLevel::kWarn;
    message << "no motor outputs on " << config.rc_out_input;
  } else {
    message << "receiving";
  }
  status.message = message.str();
  return status;
}

HealthStatus judgeMotorOutputs(const Estimator& estimator, const HealthSnapshot& before, const HealthSnapshot& now,
                               const HealthConfig& config) {
  HealthStatus status;
  const EstimatorCounters& c = now.counters;
  const InputActivity& inputs = now.inputs;
  add(&status, "accepted", c.accepted);
  for (int r = 1; r < kRejectionCount; ++r) {
    if (r != static_cast<int>(Rejection::kBadInput)) {
      add(&status, std::string("rejected ") + rejectionName(static_cast<Rejection>(r)), c.rejected[r]);
    }
  }
  for (input::Scalar scalar : input::kAllScalars) {
    add(&status, "rejected " + badInputName(scalar), c.rejected_inputs[input::index(scalar)]);
  }
  add(&status, "rejected undecodable", inputs.rc_out_undecodable);
  add(&status, "clock resets", c.clock_resets);
  const std::string last_rejection = describe(estimator.lastRejection());
  add(&status, "last rejection", last_rejection);
  if (inputs.rc_out_undecodable > 0) add(&status, "last decoding error", inputs.last_decoding_error);

  // Disarmed is the normal state on the ground, not a problem.
  std::uint64_t new_problems = 0;
  for (int r = 1; r < kRejectionCount; ++r) {
    if (r != static_cast<int>(Rejection::kDisarmed)) new_problems += c.rejected[r] - before.counters.rejected[r];
  }
  if (inputs.rc_out_undecodable > before.inputs.rc_out_undecodable) {
    status.level = HealthLevel::kError;
    status.message = config.rc_out_input + ": " + inputs.last_decoding_error;
  } else if (new_problems > 0) {
    status.level = HealthLevel::kWarn;
    status.message = last_rejection;
  } else if (inputs.last_rc_out_verdict == Rejection::kDisarmed) {
    status.message = last_rejection;
  } else {
    status.message = "ok";
  }
  return status;
}

std::string unmodelledOutputs(const PropulsionModel& model) {
  std::vector<std::string> list;
  for (Output output : kAllOutputs) {
    if (model.output(output).source == OutputSource::kNone) list.push_back(outputName(output));
  }
  return list.empty() ? "none" : joined(list);
}

HealthStatus judgeDomain(const Estimator& estimator, const HealthSnapshot& before, const HealthSnapshot& now,
                         const HealthConfig& config) {
  HealthStatus status;
  const std::uint64_t samples = now.counters.motor_samples - before.counters.motor_samples;
  const std::uint64_t outside =
      now.counters.motor_samples_outside_domain - before.counters.motor_samples_outside_domain;
  const double fraction = samples ? static_cast<double>(outside) / static_cast<double>(samples) : 0.0;
  const ModelDomain& d = estimator.model().domain();
  add(&status, "fraction outside domain", fraction);
  add(&status, "samples outside domain (total)", now.counters.motor_samples_outside_domain);
  add(&status, "domain", formatNumber(d.pwm_min_us) + "-" + formatNumber(d.pwm_max_us) + " us, " +
                             formatNumber(d.voltage_min_v) + "-" + formatNumber(d.voltage_max_v) + " V");
  add(&status, "outputs not modelled (published as NaN)", unmodelledOutputs(estimator.model()));
  if (fraction > config.domain_warn_fraction) {
    std::ostringstream message;
    message.precision(3);
    message << 100.0 * fraction << " % of motor samples outside the model's domain ("
            << treatmentOutsideDomain(d.outside) << ")";
    status.level = HealthLevel::kWarn;
    status.message = message.str();
  } else {
    status.message = "within the measured domain";
  }
  return status;
}

HealthStatus judgePayload(const Estimator& estimator) {
  HealthStatus status;
  const MassEstimate& p = estimator.output().payload;
  add(&status, "state", std::string(payloadStateName(p.state)));
  add(&status, "hovering", p.hovering);
  add(&status, "total mass (kg)", p.total_mass_kg);
  add(&status, "empty mass (kg)", p.empty_mass_kg);
  add(&status, "empty mass source", std::string(emptyMassSourceName(p.empty_mass_source)));
  add(&status, "payload mass (kg)", p.payload_mass_kg);
  add(&status, "hover", estimator.describeHover());
  const HoverVerdict& hover = estimator.output().hover;
  add(&status, "hover checks inactive", hoverCheckNames(hover.inactiveChecks()));
  add(&status, "vertical speed source", std::string(verticalSpeedSourceName(estimator.output().vertical_speed_source)));
  status.message = payloadStateName(p.state);
  // Without its signal a check passes nothing: a steady climb with no vertical speed, a tilted
  // hover with no IMU would count as hover. Said only while the window holds samples.
  if (hover.samples > 0 && hover.inactiveChecks()) {
    status.level = HealthLevel::kWarn;
    std::vector<std::string> missing;
    if (hover.inactiveChecks() & (kTiltCheck | kVerticalAccelCheck)) missing.push_back("no fresh IMU");
    if (hover.inactiveChecks() & kVerticalSpeedCheck) missing.push_back("no fresh velocity or barometer");
    status.message +=
        "; hover checks inactive: " + hoverCheckNames(hover.inactiveChecks()) + " (" + joined(missing) + ")";
  }
  return status;
}

std::string signalSource(effects::Signal signal, const HealthConfig& config) {
  if (signal == effects::Signal::kNone) return "no signal";
  return effects::sourcesOf(signal, config.signal_sources);
}

HealthStatus judgeEffects(const Estimator& estimator, const HealthSnapshot& before, const HealthSnapshot& now,
                          const HealthConfig& config) {
  HealthStatus status;
  const effects::ModelEffects& fx = estimator.model().effects();
  if (fx.empty()) {
    status.message = "none: the model has no effects";
    return status;
  }
  const effects::Signals signals = estimator.effectSignals(now.time_s);
  std::vector<std::string> applied, skipped;
  for (effects::Kind kind : effects::kAllKinds) {
    if (!fx.has(kind)) continue;
    const std::size_t k = static_cast<std::size_t>(kind);
    const std::uint64_t skips = now.counters.effect_skipped[k] - before.counters.effect_skipped[k];
    const std::uint64_t applications = now.counters.effect_applied[k] - before.counters.effect_applied[k];
    const effects::Signal signal = effects::requiredSignal(kind);
    // Skipped on a message of the period, or about to be: the signal is missing now.
    const bool missing = signal != effects::Signal::kNone && std::isnan(signals.value(signal));
    std::ostringstream value;
    value << effects::describeParameters(kind, fx) << "; applied to " << applications << ", skipped on " << skips
          << " messages since the last report";
    if (missing) value << "; " << signalSource(signal, config) << " missing or stale";
    add(&status, effects::kindName(kind), value.str());
    if (skips > 0 || missing) {
      skipped.push_back(std::string(effects::kindName(kind)) + " (" + signalSource(signal, config) +
                        " missing or stale)");
    } else {
      applied.push_back(effects::kindName(kind));
    }
  }
  if (!skipped.empty()) {
    status.level = HealthLevel::kWarn;
    status.message = "skipped: " + joined(skipped) + (applied.empty() ? std::string() : "; applied: " + joined(applied));
  } else {
    status.message = "applied: " + joined(applied);
  }
  return status;
}

}  // namespace propulsion_estimator
