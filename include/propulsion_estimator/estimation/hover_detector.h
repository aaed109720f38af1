#pragma once

#include <cstddef>
#include <string>

#include "propulsion_estimator/estimation/time_window.h"

namespace propulsion_estimator {

/// When is the vehicle hovering? Total thrust steady over a sliding window and, where an IMU or a
/// velocity source is available, small tilt, vertical speed and vertical acceleration; in the
/// spirit of ArduPilot's hover-throttle learning (vertical speed under 0.6 m/s, tilt under 5 deg).
struct HoverConfig {
  double window_s = 2.0;
  double min_window_fill = 0.8;          // fraction of window_s the samples must span, below 1
  double max_thrust_rel_std = 0.05;      // std / mean of vertical thrust over the window
  double max_tilt_deg = 5.0;
  double max_vertical_speed_m_s = 0.6;
  double max_vertical_accel_m_s2 = 1.0;  // of the window's mean vertical acceleration
  double min_mass_kg = 0.3;              // the thrust must carry at least this: not idling on the ground

  void validate() const;  // ConfigError naming the field
};

/// One sample; NaN marks what is not measured (no IMU, no velocity source).
struct HoverSample {
  double vertical_thrust_n = 0.0;
  double mass_kg = 0.0;  // mass that thrust holds
  double tilt_rad = 0.0;
  double vertical_speed_m_s = 0.0;
  double vertical_accel_m_s2 = 0.0;
};

/// Why the window is not a hover (the first condition that failed); kNone when it is.
enum class HoverBlocker {
  kNone,
  kWindowFilling,
  kLowThrust,
  kThrustUnsteady,
  kTilted,
  kClimbingOrSinking,
  kAccelerating,
  kExpired,  // no sample within window_s before now: the last verdict is no longer one
};

/// The detector's verdict on its window, with the window statistics it was based on (SI units).
struct HoverVerdict {
  bool hovering = false;
  HoverBlocker blocker = HoverBlocker::kWindowFilling;
  std::size_t samples = 0;
  double span_s = 0.0;
  double mean_thrust_n = 0.0;
  double thrust_rel_std = 0.0;
  double mean_mass_kg = 0.0;
  double max_tilt_rad = 0.0;            // NaN without IMU
  double max_abs_vertical_speed_m_s = 0.0;  // NaN without velocity
  double mean_vertical_accel_m_s2 = 0.0;    // NaN without IMU
};

/// One line for humans: "hovering: ..." or "not hovering: <why>, <window statistics>".
std::string describe(const HoverVerdict& verdict, const HoverConfig& config);

/// Keeps a sliding window of HoverSample and judges it against a HoverConfig.
class HoverDetector {
 public:
  // `capacity`: samples the window can hold (window_s times the highest expected rate).
  HoverDetector(const HoverConfig& config, std::size_t capacity);

  // Adds a sample and returns the verdict over the window. Allocates nothing.
  const HoverVerdict& add(double stamp_s, const HoverSample& sample);
  const HoverVerdict& verdict() const { return verdict_; }
  const HoverConfig& config() const { return config_; }
  void clear();
  // Forgets the window because no sample came within window_s: the verdict says kExpired.
  void expire();

 private:
  void evaluate();

  HoverConfig config_;
  TimeWindow<HoverSample> window_;
  HoverVerdict verdict_;
};

}  // namespace propulsion_estimator
