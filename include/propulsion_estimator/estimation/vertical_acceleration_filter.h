#pragma once

namespace propulsion_estimator {

/// Vertical acceleration from an accelerometer, freed of its bias. A 0.1 m/s^2 bias alone would
/// read as a 1 % mass error; but a vehicle that stays airborne has zero mean vertical acceleration
/// over tens of seconds, so a slow average of the measurement is its bias. The output is a fast
/// low-pass (against vibration) minus that slow average.
class VerticalAccelerationFilter {
 public:
  /// Longest time step, in s, one sample may stand for in the bias average: after a gap in the
  /// IMU (10 s would give one raw sample, a bump or a landing jolt, a quarter of the bias) a sample
  /// weighs as one of an IMU at 10 Hz, the slowest MAVROS publishes. The fast low-pass takes the
  /// whole gap: its old value is stale.
  static constexpr double kMaxBiasStepS = 0.1;

  /// Time constants in s of the fast low-pass and of the bias average (both > 0, validated by the owner).
  VerticalAccelerationFilter(double fast_time_constant_s, double bias_time_constant_s);

  /// `accel_m_s2`: world-vertical specific force minus g. Returns the filtered acceleration.
  double add(double stamp_s, double accel_m_s2);
  /// The filtered acceleration, m/s^2, up positive.
  double value() const { return fast_ - slow_; }
  /// Forgets everything (after a clock reset).
  void clear() { started_ = false; fast_ = slow_ = 0.0; }

 private:
  double fast_tau_s_;
  double slow_tau_s_;
  bool started_ = false;
  double last_stamp_s_ = 0.0;
  double fast_ = 0.0;
  double slow_ = 0.0;
};

}  // namespace propulsion_estimator
