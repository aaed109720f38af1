#pragma once

namespace propulsion_estimator {

/// Vertical speed from a barometer, the hover detector's fallback when no velocity topic is fresh:
/// a steady climb must not pass for a hover. The height is the hypsometric one, h = (R T / g)
/// ln(p0 / p) at the standard 15 deg C (a 10 K error changes the speed by 3.5 %, far inside the
/// hover threshold). Two first-order low-passes of the height with time constants tau_fast <
/// tau_slow each lag a steady climb at v by v tau, so v = (h_fast - h_slow) / (tau_slow - tau_fast),
/// at any sample rate and in O(1); a barometer's noise of a few Pa (tens of cm) is averaged over
/// about tau_slow.
class BarometricVerticalSpeed {
 public:
  static constexpr double kFastTimeConstantS = 0.3;  ///< s, tau_fast
  static constexpr double kSlowTimeConstantS = 1.0;  ///< s, tau_slow
  /// The speed is given once the pressure has been followed this long (both filters settled).
  static constexpr double kSettlingS = 2.0;

  /// `pressure_pa` > 0 (checked by the caller), `stamp_s` in s.
  void add(double stamp_s, double pressure_pa);
  /// Vertical speed in m/s, up positive; NaN before kSettlingS of readings.
  double value() const;
  /// Forgets the height history (the speed is NaN again for kSettlingS).
  void clear() { started_ = false; }

 private:
  bool started_ = false;
  double first_stamp_s_ = 0.0;
  double last_stamp_s_ = 0.0;
  double reference_pa_ = 0.0;
  double fast_m_ = 0.0;
  double slow_m_ = 0.0;
};

}  // namespace propulsion_estimator
