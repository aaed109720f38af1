#include "propulsion_estimator/estimation/hover_detector.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

}  // namespace

void HoverConfig::validate() const {
  requirePositive("hover/window_s", window_s);
  requirePositive("hover/min_window_fill", min_window_fill, 1.0);
  if (min_window_fill == 1.0) {
    // The window keeps samples at most window_s old: they span the whole of it only when one
    // happens to be stamped exactly window_s before the newest.
    throw FieldError("hover/min_window_fill",
                     formatNumber(min_window_fill) + " is never met: the samples span less than the whole window");
  }
  requirePositive("hover/max_thrust_rel_std", max_thrust_rel_std);
  requirePositive("hover/max_tilt_deg", max_tilt_deg);
  requirePositive("hover/max_vertical_speed_m_s", max_vertical_speed_m_s);
  requirePositive("hover/max_vertical_accel_m_s2", max_vertical_accel_m_s2);
  requirePositive("hover/min_mass_kg", min_mass_kg);
}

HoverDetector::HoverDetector(const HoverConfig& config, std::size_t capacity)
    : config_(config), window_(config.window_s, capacity) {}

void HoverDetector::clear() {
  window_.clear();
  verdict_ = HoverVerdict{};
}

void HoverDetector::expire() {
  clear();
  verdict_.blocker = HoverBlocker::kExpired;
}

const HoverVerdict& HoverDetector::add(double stamp_s, const HoverSample& sample) {
  window_.push(stamp_s, sample);
  evaluate();
  return verdict_;
}

void HoverDetector::evaluate() {
  HoverVerdict v;
  v.samples = window_.size();
  v.span_s = window_.span();
  double sum = 0.0, sum_sq = 0.0, mass = 0.0, accel = 0.0;
  double max_tilt = std::nan(""), max_speed = std::nan("");
  std::size_t accel_samples = 0;
  for (std::size_t i = 0; i < window_.size(); ++i) {
    const HoverSample& s = window_[i];
    sum += s.vertical_thrust_n;
    sum_sq += s.vertical_thrust_n * s.vertical_thrust_n;
    mass += s.mass_kg;
    // fmax ignores a NaN argument: the maxima stay NaN only if nothing was measured.
    max_tilt = std::fmax(max_tilt, std::fabs(s.tilt_rad));
    max_speed = std::fmax(max_speed, std::fabs(s.vertical_speed_m_s));
    if (!std::isnan(s.vertical_accel_m_s2)) {
      accel += s.vertical_accel_m_s2;
      ++accel_samples;
    }
  }
  const double n = static_cast<double>(std::max<std::size_t>(v.samples, 1));
  v.mean_thrust_n = sum / n;
  const double variance = std::max(sum_sq / n - v.mean_thrust_n * v.mean_thrust_n, 0.0);
  v.thrust_rel_std = v.mean_thrust_n > 0.0 ? std::sqrt(variance) / v.mean_thrust_n : 0.0;
  v.mean_mass_kg = mass / n;
  v.max_tilt_rad = max_tilt;
  v.max_abs_vertical_speed_m_s = max_speed;
  v.mean_vertical_accel_m_s2 = accel_samples ? accel / static_cast<double>(accel_samples) : std::nan("");

  if (v.samples < 2 || v.span_s < config_.min_window_fill * config_.window_s) {
    v.blocker = HoverBlocker::kWindowFilling;
  } else if (v.mean_mass_kg < config_.min_mass_kg) {
    v.blocker = HoverBlocker::kLowThrust;
  } else if (v.thrust_rel_std > config_.max_thrust_rel_std) {
    v.blocker = HoverBlocker::kThrustUnsteady;
  } else if (max_tilt * kRadToDeg > config_.max_tilt_deg) {
    v.blocker = HoverBlocker::kTilted;
  } else if (max_speed > config_.max_vertical_speed_m_s) {
    v.blocker = HoverBlocker::kClimbingOrSinking;
  } else if (std::fabs(v.mean_vertical_accel_m_s2) > config_.max_vertical_accel_m_s2) {
    v.blocker = HoverBlocker::kAccelerating;
  } else {
    v.blocker = HoverBlocker::kNone;
  }
  v.hovering = v.blocker == HoverBlocker::kNone;
  verdict_ = v;
}

std::string describe(const HoverVerdict& v, const HoverConfig& c) {
  std::ostringstream out;
  out.precision(3);
  switch (v.blocker) {
    case HoverBlocker::kNone: out << "hovering"; break;
    case HoverBlocker::kWindowFilling:
      out << "not hovering: window spans " << v.span_s << " s of the " << c.min_window_fill * c.window_s
          << " s needed";
      break;
    case HoverBlocker::kLowThrust:
      out << "not hovering: thrust holds " << v.mean_mass_kg << " kg, less than min_mass_kg " << c.min_mass_kg;
      break;
    case HoverBlocker::kThrustUnsteady:
      out << "not hovering: thrust varies by " << 100.0 * v.thrust_rel_std << " % (limit "
          << 100.0 * c.max_thrust_rel_std << " %)";
      break;
    case HoverBlocker::kTilted:
      out << "not hovering: tilt " << v.max_tilt_rad * kRadToDeg << " deg (limit " << c.max_tilt_deg << " deg)";
      break;
    case HoverBlocker::kClimbingOrSinking:
      out << "not hovering: vertical speed " << v.max_abs_vertical_speed_m_s << " m/s (limit "
          << c.max_vertical_speed_m_s << " m/s)";
      break;
    case HoverBlocker::kAccelerating:
      out << "not hovering: vertical acceleration " << v.mean_vertical_accel_m_s2 << " m/s^2 (limit "
          << c.max_vertical_accel_m_s2 << " m/s^2)";
      break;
    case HoverBlocker::kExpired:
      out << "not hovering: no sample within the last hover/window_s " << c.window_s << " s (the last verdict expired)";
      break;
  }
  out << "; window " << v.samples << " samples over " << v.span_s << " s, mean thrust " << v.mean_thrust_n
      << " N (" << v.mean_mass_kg << " kg), thrust std " << 100.0 * v.thrust_rel_std << " %";
  if (!std::isnan(v.max_tilt_rad)) out << ", max tilt " << v.max_tilt_rad * kRadToDeg << " deg";
  if (!std::isnan(v.max_abs_vertical_speed_m_s)) out << ", max |vz| " << v.max_abs_vertical_speed_m_s << " m/s";
  return out.str();
}

}  // namespace propulsion_estimator
