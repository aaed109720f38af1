#include "propulsion_estimator/gap/ground_draw.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "propulsion_estimator/model/effect_signals.h"

namespace propulsion_estimator {
namespace gap {

GroundDraw measureGroundDraw(const FlightStreams& streams, int motors, double stopped_us, double settle_s,
                             double timeout_s) {
  const auto stopped = [&](const RcOutFrame& frame) {
    for (int k = 0; k < motors; ++k) {
      if (!(frame.pwm_us[k] <= stopped_us)) return false;
    }
    return true;
  };
  std::vector<double> currents;
  std::size_t next = 0;
  double stopped_since = kNaN;  // first frame of the run of stopped frames in force; NaN: spinning
  const RcOutFrame* in_force = nullptr;
  for (const BatteryReading& reading : streams.battery) {
    while (next < streams.rc_out.size() && streams.rc_out[next].time_s <= reading.time_s) {
      in_force = &streams.rc_out[next++];
      if (!stopped(*in_force)) {
        stopped_since = kNaN;
      } else if (std::isnan(stopped_since)) {
        stopped_since = in_force->time_s;
      }
    }
    if (!in_force || reading.time_s - in_force->time_s > timeout_s || !std::isfinite(reading.current_a)) continue;
    if (std::isnan(stopped_since) || reading.time_s - stopped_since < settle_s) continue;
    currents.push_back(effects::dischargeCurrentA(reading.current_a));
  }
  GroundDraw draw;
  draw.readings = static_cast<int>(currents.size());
  if (draw.readings < kMinGroundDrawReadings) return draw;
  const auto middle = currents.begin() + currents.size() / 2;
  std::nth_element(currents.begin(), middle, currents.end());
  draw.current_a = *middle;
  return draw;
}

}  // namespace gap
}  // namespace propulsion_estimator
