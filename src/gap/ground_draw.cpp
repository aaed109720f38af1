#include "propulsion_estimator/gap/ground_draw.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace propulsion_estimator {
namespace gap {

double stoppedPwmUs(const ModelDomain& domain) { return std::min(1000.0, domain.pwm_min_us - 10.0); }

GroundDraw measureGroundDraw(const FlightStreams& streams, int motors, double stopped_us, double settle_s,
                             double timeout_s) {
  const auto stopped = [&](const RcOutFrame& frame) {
    for (int k = 0; k < motors; ++k) {
      if (!(frame.pwm_us[k] <= stopped_us)) return false;
    }
    return true;
  };
  std::vector<double> on_ground;
  double spinning_sum_a = 0.0;  // the discharge's sign as the sensor reports it
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
    if (std::isnan(stopped_since)) {
      spinning_sum_a += reading.current_a;
    } else if (reading.time_s - stopped_since >= settle_s) {
      on_ground.push_back(reading.current_a);
    }
  }
  GroundDraw draw;
  draw.readings = static_cast<int>(on_ground.size());
  if (draw.readings < kMinGroundDrawReadings) return draw;
  const auto middle = on_ground.begin() + on_ground.size() / 2;
  std::nth_element(on_ground.begin(), middle, on_ground.end());
  // Without a spinning reading the sign is the ground's own: a draw, not a charge.
  const double sign = spinning_sum_a < 0.0 || (spinning_sum_a == 0.0 && *middle < 0.0) ? -1.0 : 1.0;
  draw.current_a = sign * *middle;
  return draw;
}

}  // namespace gap
}  // namespace propulsion_estimator
