#include "propulsion_estimator/gap/airborne_stretch.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace gap {
namespace {

// One RCOut message: its time, whether every motor was armed, and the mass its model thrust holds.
struct Held {
  double time_s;
  bool armed;
  double mass_kg;
};

std::vector<Held> heldMasses(const FlightStreams& streams, const PropulsionModel& model, double disarmed_pwm_max_us) {
  std::vector<Held> held;
  held.reserve(streams.rc_out.size());
  std::size_t battery = 0;
  double voltage_v = streams.battery.empty() ? 0.0 : streams.battery.front().voltage_v;
  for (const RcOutFrame& frame : streams.rc_out) {
    while (battery < streams.battery.size() && streams.battery[battery].time_s <= frame.time_s) {
      voltage_v = streams.battery[battery++].voltage_v;
    }
    bool armed = true;
    double thrust_n = 0.0;
    for (int k = 0; k < streams.motors; ++k) {
      armed = armed && frame.pwm_us[k] > disarmed_pwm_max_us;
      OperatingPoint point;
      model.evaluate(frame.pwm_us[k], voltage_v, &point);
      thrust_n += std::isfinite(point.thrust_n) ? point.thrust_n : 0.0;
    }
    held.push_back({frame.time_s, armed, thrust_n / kStandardGravity});
  }
  return held;
}

double percentile75(std::vector<double> values) {
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(3 * values.size() / 4);
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

std::string seconds(double value) { return formatPrintf("%.1f s", value); }

}  // namespace

void AirborneSettings::validate() const {
  requireWithin("disarmed_pwm_max_us", disarmed_pwm_max_us, 0.0, 2500.0, " us");
  requirePositive("max_gap_s", max_gap_s, 60.0, " s");
  requireWithin("lift_fraction", lift_fraction, 0.1, 1.0);
  requirePositive("max_dip_s", max_dip_s, 60.0, " s");
  requireWithin("settle_s", settle_s, 0.0, 60.0, " s");
  requireWithin("end_margin_s", end_margin_s, 0.0, 60.0, " s");
  requirePositive("min_weighed_s", min_weighed_s, 3600.0, " s");
}

std::vector<AirborneStretch> findAirborneStretches(const FlightStreams& streams, const PropulsionModel& model,
                                                   const AirborneSettings& settings, std::string* why) {
  settings.validate();
  const std::vector<Held> held = heldMasses(streams, model, settings.disarmed_pwm_max_us);
  std::vector<AirborneStretch> stretches;
  double armed_s = 0.0, longest_s = 0.0;
  for (std::size_t i = 0; i < held.size();) {
    if (!held[i].armed) {
      ++i;
      continue;
    }
    std::size_t end = i + 1;  // one past the armed stretch
    while (end < held.size() && held[end].armed && held[end].time_s - held[end - 1].time_s <= settings.max_gap_s) ++end;
    std::vector<double> masses;
    for (std::size_t j = i; j < end; ++j) masses.push_back(held[j].mass_kg);
    const double lifting = settings.lift_fraction * percentile75(masses);
    armed_s += held[end - 1].time_s - held[i].time_s;
    // Runs of lifting messages; a dip shorter than max_dip_s (a descent's start) stays airborne.
    for (std::size_t j = i; j < end;) {
      if (held[j].mass_kg < lifting) {
        ++j;
        continue;
      }
      std::size_t last = j;
      for (std::size_t k = j + 1; k < end && held[k].time_s - held[last].time_s <= settings.max_dip_s; ++k) {
        if (held[k].mass_kg >= lifting) last = k;
      }
      longest_s = std::max(longest_s, held[last].time_s - held[j].time_s);
      const AirborneStretch stretch{held[j].time_s, held[last].time_s, held[j].time_s + settings.settle_s,
                                    held[last].time_s - settings.end_margin_s};
      if (stretch.end_s - stretch.start_s >= settings.min_weighed_s) stretches.push_back(stretch);
      j = last + 1;
    }
    i = end;
  }
  if (stretches.empty() && why) {
    *why = held.empty() ? "no RCOut message"
           : armed_s == 0.0
               ? "no motor output above disarmed_pwm_max_us " + std::to_string(static_cast<int>(settings.disarmed_pwm_max_us)) +
                     " us on every motor (never armed)"
               : "armed for " + seconds(armed_s) + " in all, the longest stretch holding its mass " + seconds(longest_s) +
                     ": less than the " + seconds(settings.settle_s + settings.end_margin_s + settings.min_weighed_s) +
                     " a weighed stretch needs with its settling";
  }
  return stretches;
}

std::vector<ManifestSegment> airborneSegments(const FlightStreams& streams, const PropulsionModel& model,
                                              const std::vector<double>& mass_kg, const AirborneSettings& settings,
                                              std::vector<AirborneStretch>* found) {
  std::string why;
  const std::vector<AirborneStretch> stretches = findAirborneStretches(streams, model, settings, &why);
  if (stretches.empty()) throw DataError(streams.source + ": no airborne stretch: " + why);
  if (mass_kg.size() > 1 && mass_kg.size() != stretches.size()) {
    std::vector<std::string> list;
    for (const AirborneStretch& s : stretches) list.push_back(seconds(s.lift_off_s) + " to " + seconds(s.touchdown_s));
    throw DataError(streams.source + ": " + std::to_string(mass_kg.size()) + " masses for " +
                    std::to_string(stretches.size()) + " airborne stretches (" + joined(list) + ")");
  }
  std::vector<ManifestSegment> segments;
  for (std::size_t k = 0; k < stretches.size(); ++k) {
    segments.push_back({stretches[k].start_s, stretches[k].end_s, mass_kg.size() == 1 ? mass_kg[0] : mass_kg[k]});
  }
  if (found) *found = stretches;
  return segments;
}

}  // namespace gap
}  // namespace propulsion_estimator
