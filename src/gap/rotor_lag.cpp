#include "propulsion_estimator/gap/rotor_lag.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace propulsion_estimator {
namespace gap {
namespace {

constexpr double kMaxTimeConstantS = 0.3;
constexpr double kStepS = 0.005;
constexpr double kCoarseStepS = 0.02;
constexpr double kMinWithinBlockStdUs = 2.0;

// One frame of a weighed segment: its block (flight, segment, index), collective and vertical force.
struct FrameSample {
  long block = 0;
  double collective_us = 0.0;
  double force_up_m_s2 = 0.0;
};

// The weighed frames with a fresh IMU reading (within 0.1 s), `commands` giving the collective.
void collectFrames(const Flight& flight, const std::vector<RcOutFrame>& commands, int motors, double block_s,
                   long first_block, std::vector<FrameSample>* out) {
  const std::vector<ImuReading>& imus = flight.streams.imu;
  if (imus.empty()) return;
  const auto earlier = [](const auto& reading, double time_s) { return reading.time_s < time_s; };
  for (std::size_t s = 0; s < flight.segments.size(); ++s) {
    const ManifestSegment& segment = flight.segments[s];
    auto imu = std::lower_bound(imus.begin(), imus.end(), segment.start_s, earlier);
    for (auto frame = std::lower_bound(commands.begin(), commands.end(), segment.start_s, earlier);
         frame != commands.end() && frame->time_s <= segment.end_s; ++frame) {
      while (imu != imus.end() && imu->time_s < frame->time_s) ++imu;
      const auto nearest = imu == imus.end() || (imu != imus.begin() && frame->time_s - (imu - 1)->time_s <
                                                                            imu->time_s - frame->time_s)
                               ? imu - 1
                               : imu;
      if (std::abs(nearest->time_s - frame->time_s) > 0.1) continue;
      double collective = 0.0;
      for (int k = 0; k < motors; ++k) collective += frame->pwm_us[k] / motors;
      const long index = static_cast<long>((frame->time_s - segment.start_s) / block_s);
      out->push_back({first_block + static_cast<long>(s) * 100000 + index, collective,
                      (nearest->orientation * nearest->specific_force_m_s2).z()});
    }
  }
}

// Sums of the within-block (demeaned) products.
struct Moments {
  double xx = 0.0, yy = 0.0, xy = 0.0;
  long n = 0;
};

Moments withinBlockMoments(const std::vector<FrameSample>& frames) {
  std::map<long, std::array<double, 3>> sums;  // per block: n, sum x, sum y
  for (const FrameSample& f : frames) {
    auto& s = sums[f.block];
    s[0] += 1.0, s[1] += f.collective_us, s[2] += f.force_up_m_s2;
  }
  Moments m;
  for (const FrameSample& f : frames) {
    const auto& s = sums[f.block];
    if (s[0] < 3.0) continue;
    const double x = f.collective_us - s[1] / s[0], y = f.force_up_m_s2 - s[2] / s[0];
    m.xx += x * x, m.yy += y * y, m.xy += x * y;
    ++m.n;
  }
  return m;
}

}  // namespace

std::vector<RcOutFrame> laggedCommands(const std::vector<RcOutFrame>& rc_out, int motors, double time_constant_s) {
  if (time_constant_s <= 0.0 || rc_out.empty()) return rc_out;
  std::vector<RcOutFrame> lagged = rc_out;
  for (std::size_t i = 1; i < lagged.size(); ++i) {
    const double dt = std::max(0.0, rc_out[i].time_s - rc_out[i - 1].time_s);
    // Exact for a command held between frames (zero-order hold, as an ESC receives it).
    const double keep = std::exp(-dt / time_constant_s);
    for (int k = 0; k < motors; ++k) {
      lagged[i].pwm_us[k] = rc_out[i - 1].pwm_us[k] + (lagged[i - 1].pwm_us[k] - rc_out[i - 1].pwm_us[k]) * keep;
    }
  }
  return lagged;
}

std::optional<RotorLag> identifyRotorLag(const std::vector<Flight>& flights, int motors, double block_s) {
  // How well the command lagged by `tau` explains the force within blocks; nullopt without data.
  const auto fitAt = [&](double tau) -> std::optional<RotorLag> {
    std::vector<FrameSample> frames;
    for (std::size_t f = 0; f < flights.size(); ++f) {
      collectFrames(flights[f], laggedCommands(flights[f].streams.rc_out, motors, tau), motors, block_s,
                    static_cast<long>(f) * 100000000L, &frames);
    }
    const Moments m = withinBlockMoments(frames);
    if (m.n < 50 || !(std::sqrt(m.xx / m.n) >= kMinWithinBlockStdUs) || !(m.yy > 0.0)) return std::nullopt;
    return RotorLag{tau, m.xy * m.xy / (m.xx * m.yy), static_cast<int>(m.n)};
  };
  // A coarse grid, then the fine one around its best: the fit is smooth in the time constant. The
  // data gate is the unlagged command's; a long lag smooths the command below it, which only
  // rules that lag out.
  std::optional<RotorLag> best = fitAt(0.0);
  if (!best) return std::nullopt;
  for (double tau = kCoarseStepS; tau <= kMaxTimeConstantS + 1e-9; tau += kCoarseStepS) {
    const std::optional<RotorLag> fit = fitAt(tau);
    if (fit && fit->fit_r2 > best->fit_r2) best = fit;
  }
  const double centre = best->time_constant_s;
  for (double tau = std::max(0.0, centre - kCoarseStepS); tau <= centre + kCoarseStepS + 1e-9; tau += kStepS) {
    const std::optional<RotorLag> fit = fitAt(tau);
    if (fit && fit->fit_r2 > best->fit_r2) best = fit;
  }
  return best;
}

}  // namespace gap
}  // namespace propulsion_estimator
