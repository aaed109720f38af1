#include "propulsion_estimator/estimation/hover_detector.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

}  // namespace

void HoverConfig::validate() const {
  requirePositive("hover/window_s", window_s);
  requirePositive("hover/min_window_fill", min_window_fill, 1.0);
  // The window keeps whole bins of window_s / kBins: its samples always span less than window_s,
  // and at least (kBins - 1) / kBins of it once the window is full.
  constexpr double kBins = static_cast<double>(BinnedWindow<HoverStatistics>::kBins);
  if (min_window_fill > (kBins - 1.0) / kBins) {
    throw FieldError("hover/min_window_fill",
                     formatNumber(min_window_fill) + " is never reliably met: the window keeps its samples in " +
                         formatNumber(kBins) + " bins and spans at least " + formatPrintf("%.4g", (kBins - 1.0) / kBins) +
                         " of hover/window_s");
  }
  requirePositive("hover/max_thrust_rel_std", max_thrust_rel_std);
  requirePositive("hover/max_tilt_deg", max_tilt_deg);
  requirePositive("hover/max_vertical_speed_m_s", max_vertical_speed_m_s);
  requirePositive("hover/max_vertical_accel_m_s2", max_vertical_accel_m_s2);
  requirePositive("hover/min_mass_kg", min_mass_kg);
}

void HoverStatistics::add(const HoverSample& s) {
  thrust_n.add(s.vertical_thrust_n);
  mass_sum_kg += s.mass_kg;
  if (!std::isnan(s.tilt_rad)) {
    max_tilt_rad = std::fmax(max_tilt_rad, std::fabs(s.tilt_rad));  // fmax ignores the initial NaN
    ++tilt_samples;
  }
  if (!std::isnan(s.vertical_speed_m_s)) {
    max_abs_vertical_speed_m_s = std::fmax(max_abs_vertical_speed_m_s, std::fabs(s.vertical_speed_m_s));
    ++vertical_speed_samples;
  }
  if (!std::isnan(s.vertical_accel_m_s2)) {
    vertical_accel_sum_m_s2 += s.vertical_accel_m_s2;
    ++vertical_accel_samples;
  }
}

void HoverStatistics::merge(const HoverStatistics& o) {
  thrust_n.merge(o.thrust_n);
  mass_sum_kg += o.mass_sum_kg;
  max_tilt_rad = std::fmax(max_tilt_rad, o.max_tilt_rad);
  tilt_samples += o.tilt_samples;
  max_abs_vertical_speed_m_s = std::fmax(max_abs_vertical_speed_m_s, o.max_abs_vertical_speed_m_s);
  vertical_speed_samples += o.vertical_speed_samples;
  vertical_accel_sum_m_s2 += o.vertical_accel_sum_m_s2;
  vertical_accel_samples += o.vertical_accel_samples;
}

std::string hoverCheckNames(std::uint8_t mask) {
  std::vector<std::string> names;
  for (const auto& [bit, name] : {std::pair<std::uint8_t, const char*>{kTiltCheck, "tilt"},
                                  {kVerticalSpeedCheck, "vertical speed"},
                                  {kVerticalAccelCheck, "vertical acceleration"}}) {
    if (mask & bit) names.push_back(name);
  }
  return names.empty() ? "none" : joined(names);
}

HoverDetector::HoverDetector(const HoverConfig& config) : config_(config), window_(config.window_s) {}

void HoverDetector::clear() {
  window_.clear();
  verdict_ = HoverVerdict{};
}

void HoverDetector::expire() {
  clear();
  verdict_.blocker = HoverBlocker::kExpired;
}

const HoverVerdict& HoverDetector::add(double stamp_s, const HoverSample& sample) {
  window_.add(stamp_s, sample);
  evaluate();
  return verdict_;
}

void HoverDetector::evaluate() {
  const HoverStatistics stats = window_.total();
  HoverVerdict v;
  v.samples = static_cast<std::size_t>(stats.thrust_n.count);
  v.span_s = window_.span();
  const double n = static_cast<double>(std::max<std::size_t>(v.samples, 1));
  v.mean_thrust_n = stats.thrust_n.mean;
  v.thrust_rel_std = v.mean_thrust_n > 0.0 ? std::sqrt(stats.thrust_n.variance()) / v.mean_thrust_n : 0.0;
  v.mean_mass_kg = stats.mass_sum_kg / n;
  v.max_tilt_rad = stats.max_tilt_rad;
  v.max_abs_vertical_speed_m_s = stats.max_abs_vertical_speed_m_s;
  v.mean_vertical_accel_m_s2 = stats.vertical_accel_samples
                                   ? stats.vertical_accel_sum_m_s2 / static_cast<double>(stats.vertical_accel_samples)
                                   : kNaN;
  v.tilt_samples = static_cast<std::size_t>(stats.tilt_samples);
  v.vertical_speed_samples = static_cast<std::size_t>(stats.vertical_speed_samples);
  v.vertical_accel_samples = static_cast<std::size_t>(stats.vertical_accel_samples);
  // A signal that went stale within the window leaves samples no check saw (a climb while the
  // velocity was missing): the window is not judged until the signal is back throughout.
  const bool gap = (v.tilt_samples && v.tilt_samples < v.samples) ||
                   (v.vertical_speed_samples && v.vertical_speed_samples < v.samples) ||
                   (v.vertical_accel_samples && v.vertical_accel_samples < v.samples);

  if (v.samples < 2 || v.span_s < config_.min_window_fill * config_.window_s) {
    v.blocker = HoverBlocker::kWindowFilling;
  } else if (v.mean_mass_kg < config_.min_mass_kg) {
    v.blocker = HoverBlocker::kLowThrust;
  } else if (v.thrust_rel_std > config_.max_thrust_rel_std) {
    v.blocker = HoverBlocker::kThrustUnsteady;
  } else if (gap) {
    v.blocker = HoverBlocker::kSignalGap;
  } else if (v.max_tilt_rad * kRadToDeg > config_.max_tilt_deg) {
    v.blocker = HoverBlocker::kTilted;
  } else if (v.max_abs_vertical_speed_m_s > config_.max_vertical_speed_m_s) {
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
    case HoverBlocker::kSignalGap:
      out << "not hovering: a check's signal is missing on part of the window (tilt on " << v.tilt_samples
          << ", vertical speed on " << v.vertical_speed_samples << ", vertical acceleration on "
          << v.vertical_accel_samples << " of " << v.samples << " samples)";
      break;
    case HoverBlocker::kExpired:
      out << "not hovering: no sample within the last hover/window_s " << c.window_s << " s (the last verdict expired)";
      break;
  }
  out << "; window " << v.samples << " samples over " << v.span_s << " s, mean thrust " << v.mean_thrust_n
      << " N (" << v.mean_mass_kg << " kg), thrust std " << 100.0 * v.thrust_rel_std << " %";
  if (!std::isnan(v.max_tilt_rad)) out << ", max tilt " << v.max_tilt_rad * kRadToDeg << " deg";
  if (!std::isnan(v.max_abs_vertical_speed_m_s)) out << ", max |vz| " << v.max_abs_vertical_speed_m_s << " m/s";
  if (v.inactiveChecks() && v.blocker != HoverBlocker::kExpired) {
    out << "; checks inactive: " << hoverCheckNames(v.inactiveChecks());
  }
  return out.str();
}

}  // namespace propulsion_estimator
