#pragma once

#include <cstdint>
#include <string>

#include "propulsion_estimator/onboard/health_summary.h"
#include "propulsion_estimator/onboard/onboard_session.h"

namespace propulsion_estimator {

/// What the node itself observes of its ESC telemetry topics (the session sees decoded messages only).
struct EscInputActivity {
  std::string topics;               ///< "ESCTELEMETRY, ESCSTATUS" as subscribed, "-" for one not subscribed
  std::uint64_t received = 0;       ///< messages on either topic
  std::uint64_t undecodable = 0;    ///< of a wrong type or malformed
  std::string last_error;           ///< why the last undecodable one was refused
};

/// "ESC telemetry": the live model check at `now_s` (per-motor hover ratios, supply resistance,
/// mass views). OK while no telemetry arrives; WARN while some motor's telemetry is stale, or
/// when the check flags a propeller, a motor or ESC, or the supply.
HealthStatus judgeEscTelemetry(const OnboardSession& session, double now_s, const EscInputActivity& activity);

}  // namespace propulsion_estimator
