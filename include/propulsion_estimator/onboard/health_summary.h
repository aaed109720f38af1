#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/model/effect_signals.h"

namespace propulsion_estimator {

/// Severity of a health status, in the order of diagnostic_msgs/DiagnosticStatus.
enum class HealthLevel { kOk, kWarn, kError };

/// One diagnostic task's verdict: its level, one line saying why, and the values shown with it
/// (formatted as diagnostic_updater formats numbers, booleans as "True"/"False").
struct HealthStatus {
  HealthLevel level = HealthLevel::kOk;  ///< the diagnostic's severity
  std::string message;  ///< one line saying why
  std::vector<std::pair<std::string, std::string>> values;  ///< name and value pairs shown with it
};

/// The node's inputs, counted on arrival, before the estimator sees them.
enum class NodeInput { kRcOut = 0, kBattery, kImu, kVelocity };
constexpr int kNodeInputCount = 4;  ///< number of NodeInput values

/// What the node itself observes of its inputs since it started (the estimator counts only what
/// reaches it).
struct InputActivity {
  std::array<std::uint64_t, kNodeInputCount> received{};  ///< messages per NodeInput
  std::uint64_t rc_out_undecodable = 0;       ///< wrong type or malformed: never reached the estimator
  std::string last_decoding_error;            ///< why the last undecodable one was refused
  std::uint64_t imu_without_orientation = 0;  ///< REP-145 covariance -1: skipped
  Rejection last_rc_out_verdict = Rejection::kNone;  ///< the estimator's answer to the last decoded one
};

/// The counts at one instant; a diagnostics period runs between two of them.
struct HealthSnapshot {
  double time_s = 0.0;  ///< the estimator's clock (receipt times)
  InputActivity inputs;  ///< the node's counts
  EstimatorCounters counters;  ///< the estimator's counts
};

/// How the verdicts name the inputs, and the limit they apply that the estimator does not hold.
struct HealthConfig {
  std::string battery_input = "battery";     ///< e.g. the battery topic
  std::string rc_out_input = "motor outputs";  ///< e.g. the RCOut topic
  effects::SignalSources signal_sources;  ///< where the effects' signals come from, for the Effects verdict
  /// Share of motor samples outside the model's domain per period above which "Model domain" warns.
  double domain_warn_fraction = 0.2;

  /// Throws FieldError naming domain_warn_fraction and its value unless it is in [0, 1].
  void validate() const;
};

/// "Inputs": rates, battery age. ERROR while estimates stop for want of a fresh voltage; WARN
/// when no motor outputs arrived in the period.
HealthStatus judgeInputs(const Estimator& estimator, const HealthSnapshot& before, const HealthSnapshot& now,
                         const HealthConfig& config);

/// "Motor outputs": accepted and refused counts. ERROR when a message could not be decoded in the
/// period; WARN with the last refusal when one other than disarmed happened; OK with the reason
/// while disarmed.
HealthStatus judgeMotorOutputs(const Estimator& estimator, const HealthSnapshot& before, const HealthSnapshot& now,
                               const HealthConfig& config);

/// "current, power, efficiency": the outputs the model does not have (`none`), published as NaN;
/// "none" when it has them all.
std::string unmodelledOutputs(const PropulsionModel& model);

/// "Model domain": WARN when the share of motor samples outside the model's domain in the period
/// exceeds domain_warn_fraction. Its values name the outputs the model lacks (not a warning: the
/// model says so).
HealthStatus judgeDomain(const Estimator& estimator, const HealthSnapshot& before, const HealthSnapshot& now,
                         const HealthConfig& config);

/// "Payload": the payload state, the masses, the hover detector's verdict and where its vertical
/// speed came from. WARN, naming them, while the hover window holds samples on which a check was
/// inactive for want of its signal (no fresh IMU, no fresh velocity or barometer); OK otherwise.
HealthStatus judgePayload(const Estimator& estimator);

/// "battery current on /mavros/battery", ...: a signal of the model's effects and where it comes from.
std::string signalSource(effects::Signal signal, const HealthConfig& config);

/// "Effects": per effect of the model, its parameters and on how many messages of the period it was
/// applied or skipped. WARN naming each correction skipped in the period or whose signal is missing
/// or stale now (before take-off too), with the corrections applied; OK listing them, or "none".
HealthStatus judgeEffects(const Estimator& estimator, const HealthSnapshot& before, const HealthSnapshot& now,
                          const HealthConfig& config);

}  // namespace propulsion_estimator
