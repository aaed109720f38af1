#pragma once

#include <optional>
#include <vector>

#include "propulsion_estimator/logs/flight_streams.h"

namespace propulsion_estimator {
namespace gap {

/// The rotors' spin-up lag as a flight shows it: a first-order lag from the commanded pulse width
/// to the thrust, time constant in s. Identified from the lag between the collective command and
/// the vertical specific force inside each block (what is left of both once each block's mean is
/// taken off is the transient, where the lag shows), or given from a bench step response.
struct RotorLag {
  double time_constant_s = 0.0;  ///< s; 0: no lag modelled
  double fit_r2 = 0.0;  ///< share of the within-block variance of the vertical force the lagged command explains
  int frames = 0;  ///< frames of the weighed segments it was identified on
};

/// Identifies the time constant, 0..0.3 s to 5 ms, as the one whose lagged collective (the
/// mean over `motors` of each motor's lagged pulse width) best explains the vertical specific force
/// within `block_s` windows of the weighed segments, pooled over `flights`. nullopt when the
/// flights hold no IMU or too little change of command within their blocks (a collective standard
/// deviation within blocks under 2 us) to tell one lag from another. Does not throw.
std::optional<RotorLag> identifyRotorLag(const std::vector<Flight>& flights, int motors, double block_s);

/// Each motor's pulse width through the first-order lag of `time_constant_s` (s), frame by frame
/// from the log's first frame (which starts the lag at rest on its own value). Same frames and
/// times as `rc_out`; `time_constant_s` <= 0 returns them unchanged. Does not throw.
std::vector<RcOutFrame> laggedCommands(const std::vector<RcOutFrame>& rc_out, int motors, double time_constant_s);

}  // namespace gap
}  // namespace propulsion_estimator
