#pragma once

namespace propulsion_estimator {

/// Lets through at most `rate_hz` events per second of their stamps (s), on a fixed schedule: an
/// event is admitted once the next slot is within half a period (so that 50 Hz stamps jittering
/// by milliseconds pass a 50 Hz limit whole), and the slot after it is one period later, so that
/// 400 Hz events through a 50 Hz limit give 50 Hz on average, not the 44 Hz of "a period since the
/// last one". After a pause longer than a period, or stamps going back (a replay restarted), the
/// schedule restarts at the event. A rate of 0 admits every event.
class RateLimiter {
 public:
  /// `rate_hz` >= 0 (validated by the owner's parameters).
  explicit RateLimiter(double rate_hz) : period_s_(rate_hz > 0.0 ? 1.0 / rate_hz : 0.0) {}

  /// Whether the event stamped `stamp_s` (s) passes; advances the schedule when it does.
  bool admit(double stamp_s) {
    if (period_s_ == 0.0) return true;
    const bool restart = !started_ || stamp_s < last_s_ || stamp_s > due_s_ + period_s_;
    last_s_ = stamp_s;
    if (!restart && stamp_s < due_s_ - 0.5 * period_s_) return false;
    due_s_ = (restart ? stamp_s : due_s_) + period_s_;
    started_ = true;
    return true;
  }

 private:
  double period_s_;
  bool started_ = false;
  double due_s_ = 0.0;   ///< when the next event may pass
  double last_s_ = 0.0;  ///< the previous event's stamp, admitted or not
};

}  // namespace propulsion_estimator
