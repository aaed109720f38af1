#include "propulsion_estimator/gap/blocks.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/gap/rotor_lag.h"
#include "propulsion_estimator/model/effect_signals.h"

namespace propulsion_estimator {
namespace gap {
namespace {

// The latest reading at or before a time, walking forward through a time-ordered stream.
template <typename Reading>
class Cursor {
 public:
  explicit Cursor(const std::vector<Reading>& stream) : stream_(stream) {}

  // The reading in force at `time_s` and no older than `timeout_s`, or nullptr.
  const Reading* at(double time_s, double timeout_s) {
    while (next_ < stream_.size() && stream_[next_].time_s <= time_s) ++next_;
    if (next_ == 0) return nullptr;
    const Reading& latest = stream_[next_ - 1];
    return time_s - latest.time_s <= timeout_s ? &latest : nullptr;
  }

 private:
  const std::vector<Reading>& stream_;
  std::size_t next_ = 0;
};

// How much a block's collective command moved, whatever the log's rate: the change of its
// least-squares trend across the block plus the spread of its noise about the trend. A frame-by-frame
// range grows with the frames a noisy command has (10 us of noise spans about 37 us in 20 frames, 60
// us in 400); the trend and the noise's standard deviation do not. The noise counts as the
// range 20 frames of it span on average (3.7 standard deviations): the rate max_pwm_change_us was
// calibrated at.
struct CommandSteadiness {
  static constexpr double kNoiseRange = 3.7;
  int n = 0;
  double t0 = 0.0, st = 0.0, stt = 0.0, sc = 0.0, stc = 0.0, scc = 0.0, last_t = 0.0, c0 = 0.0;

  void add(double time_s, double collective_us) {
    if (n == 0) {
      t0 = time_s;
      c0 = collective_us;
    }
    // Relative to the first frame: sums of absolute times and pulse widths would cancel.
    const double t = time_s - t0, c = collective_us - c0;
    ++n;
    st += t;
    stt += t * t;
    sc += c;
    stc += t * c;
    scc += c * c;
    last_t = t;
  }
  double changeUs() const {
    if (n < 3) return 0.0;
    const double var_t = stt - st * st / n;
    const double cov = stc - st * sc / n;
    const double var_c = scc - sc * sc / n;
    const double slope = var_t > 0.0 ? cov / var_t : 0.0;
    const double residual = std::max(0.0, var_c - slope * cov) / n;
    // The trend counts beyond what the noise alone tilts a line by (two standard errors of the
    // slope): a noisy steady command would otherwise read a change that shrinks with its frames.
    const double slope_error = var_t > 0.0 ? std::sqrt(residual / var_t) : 0.0;
    const double trend = std::max(0.0, std::abs(slope) - 2.0 * slope_error) * last_t;
    return trend + kNoiseRange * std::sqrt(residual);
  }
};

// Sums of one block; a signal is averaged only when every frame of the block had it.
struct Accumulator {
  int frames = 0;
  double first_time = 0.0, last_time = 0.0;
  std::array<double, kMaxMotors> pwm{};
  std::array<double, kMaxMotors> axis{};
  double voltage = 0.0, current = 0.0, force_up = 0.0, time = 0.0;
  int current_frames = 0, imu_frames = 0;
  std::array<double, kMaxMotors> rpm{};
  std::array<int, kMaxMotors> rpm_frames{};
  // The effects' signals but the battery current (averaged with the block's current), by Signal.
  std::array<double, effects::kSignalCount> signal{};
  std::array<int, effects::kSignalCount> signal_frames{};
  double altitude = 0.0;
  int altitude_frames = 0;
  CommandSteadiness steadiness;

  // One frame's pulse widths, the rotors' vertical axes (level without attitude) and the ESCs'
  // speeds where telemetry is fresh (ESC i drives RCOut channel i + 1, motor i).
  void addMotors(const RcOutFrame& frame, int motors, const Vehicle& vehicle, const ImuReading* imu,
                 const EscTelemetryReading* telemetry) {
    double collective = 0.0;
    for (int k = 0; k < motors; ++k) collective += frame.pwm_us[k] / motors;
    steadiness.add(frame.time_s, collective);
    for (int k = 0; k < motors; ++k) {
      pwm[k] += frame.pwm_us[k];
      axis[k] += imu ? (imu->orientation * vehicle.rotors[k].thrust_axis).z() : vehicle.rotors[k].thrust_axis.z();
    }
    for (int k = 0; telemetry && k < std::min(motors, telemetry->escs); ++k) {
      if (!std::isfinite(telemetry->rpm[k])) continue;
      rpm[k] += telemetry->rpm[k];
      ++rpm_frames[k];
    }
  }

  void addSignals(const effects::Signals& prepared) {
    for (effects::Signal which : effects::allSignals()) {
      const double value = prepared.value(which);
      const int k = static_cast<int>(which);
      if (std::isfinite(value)) {
        signal[k] += value;
        ++signal_frames[k];
      }
    }
  }
  double meanSignal(effects::Signal which) const {
    const int k = static_cast<int>(which);
    return signal_frames[k] == frames ? signal[k] / frames : kNaN;
  }

  // The block's averages (without its place in the flight, mass and truth); frames > 0.
  Block average(int motors, double hover_max_vertical_speed_m_s) const {
    Block block;
    block.time_s = time / frames;
    for (int k = 0; k < motors; ++k) {
      block.pwm_us[k] = pwm[k] / frames;
      block.axis_up[k] = axis[k] / frames;
      // Telemetry drops packets: half the block's frames with a fresh speed average its noise.
      block.rpm[k] = 2 * rpm_frames[k] >= frames ? rpm[k] / rpm_frames[k] : kNaN;
    }
    block.voltage_v = voltage / frames;
    block.current_a = current_frames == frames ? current / frames : kNaN;
    block.specific_force_up_m_s2 = imu_frames == frames ? force_up / frames : kStandardGravity;
    for (effects::Signal which : effects::allSignals()) block.signals.set(which, meanSignal(which));
    block.signals.set(effects::Signal::kBatteryCurrent, block.current_a);
    block.altitude_m = altitude_frames == frames ? altitude / frames : kNaN;
    const double vertical_speed = block.signals.value(effects::Signal::kVerticalSpeed);
    block.hover = !std::isfinite(vertical_speed) || std::abs(vertical_speed) < hover_max_vertical_speed_m_s;
    block.pwm_change_us = steadiness.changeUs();
    block.accel_up_m_s2 = block.specific_force_up_m_s2 - kStandardGravity;
    return block;
  }
};

// Whether the node refuses the block: a motor outside the domain of a model whose policy is reject.
bool rejectedOutside(const Block& block, const ModelDomain& domain, int motors) {
  return domain.outside == OutsideDomain::kReject && !insideDomain(block, domain, motors);
}

// s; a rotor spins down within this after its command stops.
constexpr double kGroundDrawSettleS = 1.0;

bool hasCurrent(const std::vector<BatteryReading>& battery) {
  return std::any_of(battery.begin(), battery.end(),
                     [](const BatteryReading& reading) { return std::isfinite(reading.current_a); });
}

// The readings of the signals the effects read, in force at each frame (Cursor's rules).
struct SignalCursors {
  explicit SignalCursors(const FlightStreams& streams)
      : speed(streams.vertical_speed_m_s), horizontal_velocity(streams.horizontal_velocity) {
    for (const std::vector<ScalarReading>& readings : streams.inputs) inputs.emplace_back(readings);
  }

  effects::RawSignals at(double time_s, double timeout_s, const BatteryReading& battery, const ImuReading* imu) {
    const auto value = [&](Cursor<ScalarReading>& cursor) {
      const ScalarReading* reading = cursor.at(time_s, timeout_s);
      return reading ? reading->value : kNaN;
    };
    effects::RawSignals raw;
    raw.battery_current_a = battery.current_a;
    if (imu) {
      const Eigen::Vector3d body_z = imu->orientation * Eigen::Vector3d::UnitZ();
      raw.body_z_east = body_z.x();
      raw.body_z_north = body_z.y();
      raw.body_z_up = body_z.z();
    }
    raw.vertical_speed_m_s = value(speed);
    const HorizontalVelocityReading* horizontal = horizontal_velocity.at(time_s, timeout_s);
    if (horizontal) {
      raw.velocity_east_m_s = horizontal->east_m_s;
      raw.velocity_north_m_s = horizontal->north_m_s;
    }
    for (int k = 0; k < input::kScalarCount; ++k) raw.inputs[k] = value(inputs[k]);
    return raw;
  }

  Cursor<ScalarReading> speed;
  Cursor<HorizontalVelocityReading> horizontal_velocity;
  std::vector<Cursor<ScalarReading>> inputs;  // by input::index
};

std::string segmentName(const Flight& flight, int index) {
  const ManifestSegment& segment = flight.segments[index];
  return flight.name + ": segment " + std::to_string(index + 1) + " (" + formatNumber(segment.start_s) + "-" +
         formatNumber(segment.end_s) + " s)";
}

// Why segment `index` of `flight` lies outside its log's rc/out span; a damaged log's break named
// when the segment ends past it.
std::string outsideTheLog(const Flight& flight, int index, double log_start, double log_end) {
  const bool past_the_break = !flight.damage.empty() && flight.segments[index].end_s > log_end;
  return segmentName(flight, index) + " lies outside the log's rc/out span " + formatPrintf("%.2f", log_start) + "-" +
         formatPrintf("%.2f", log_end) + " s" + (past_the_break ? " (the log is damaged and read only up to there)" : "");
}

// Why a segment gave no block, with the counts.
std::string nothingInSegment(const std::string& name, int without_attitude, int frames, int without_battery,
                             double timeout_s) {
  if (without_attitude > 0) {
    return name + ": none of its " + std::to_string(without_attitude) +
           " blocks has the attitude on every frame (no IMU orientation within " + formatNumber(timeout_s) + " s)";
  }
  if (frames == 0) return name + " holds no rc/out frame";
  return name + " has no rc/out with a fresh battery voltage (" + std::to_string(without_battery) + " of its " +
         std::to_string(frames) + " rc/out frames without a battery voltage within " + formatNumber(timeout_s) + " s)";
}

}  // namespace

bool isQuasiSteady(const Block& block, double max_pwm_change_us, double max_accel_m_s2) {
  return block.pwm_change_us <= max_pwm_change_us && std::abs(block.accel_up_m_s2) <= max_accel_m_s2;
}

bool insideDomain(const Block& block, const ModelDomain& domain, int motors) {
  for (int k = 0; k < motors; ++k) {
    if (!domain.contains(block.pwm_us[k], block.voltage_v)) return false;
  }
  return true;
}

FlightBlocks cutIntoBlocks(const Flight& flight, int flight_index, const Vehicle& vehicle, const BlockConfig& config,
                           int first_group) {
  FlightBlocks result;
  const FlightStreams& streams = flight.streams;
  result.has_imu = !streams.imu.empty();
  result.has_current = hasCurrent(streams.battery);
  if (streams.rc_out.empty() || streams.battery.empty()) {
    result.skipped.push_back(flight.name + ": no rc/out or battery messages");
    return result;
  }
  if (!result.has_imu) {
    result.assumptions.push_back(flight.name + ": no IMU; the vertical force is taken as the weight (level, steady flight)");
  }
  const double log_start = streams.rc_out.front().time_s;
  const double log_end = streams.rc_out.back().time_s;
  const double flight_start = flight.segments.empty() ? 0.0 : flight.segments.front().start_s;
  const int motors = config.motors;
  const std::vector<RcOutFrame> commands = laggedCommands(streams.rc_out, motors, config.rotor_time_constant_s);
  result.ground_draw =
      measureGroundDraw(streams, motors, stoppedPwmUs(config.domain), kGroundDrawSettleS, config.signal_timeout_s);
  int group = first_group;

  for (int s = 0; s < static_cast<int>(flight.segments.size()); ++s) {
    const ManifestSegment& segment = flight.segments[s];
    if (segment.start_s < log_start || segment.end_s > log_end) {
      result.skipped.push_back(outsideTheLog(flight, s, log_start, log_end));
      continue;
    }
    Cursor<BatteryReading> battery(streams.battery);
    Cursor<ImuReading> imu(streams.imu);
    Cursor<ScalarReading> altitude(streams.altitude_m);
    Cursor<EscTelemetryReading> esc(streams.esc);
    SignalCursors signals(streams);
    const double timeout = config.signal_timeout_s;
    const int blocks_per_group = std::max(1, static_cast<int>(std::lround(config.group_s / config.block_s)));
    int block_in_segment = 0;
    int usable = 0, without_attitude = 0, rejected = 0, frames = 0, without_battery = 0;

    Accumulator acc;
    int current_block = 0;
    auto flush = [&]() {
      // A segment's last block may hold a frame or two: too few to average its noise, it is dropped.
      if (acc.frames == 0 || acc.last_time - acc.first_time < 0.5 * config.block_s) {
        acc = Accumulator();
        return;
      }
      Block block = acc.average(motors, config.hover_max_vertical_speed_m_s);
      if (std::isfinite(result.ground_draw.current_a)) block.current_a -= result.ground_draw.current_a;
      block.flight = flight_index;
      block.segment = s;
      block.group = group + block_in_segment / blocks_per_group;
      block.flight_time_s = block.time_s - flight_start;
      block.mass_kg = segment.mass_kg;
      block.truth_n = block.mass_kg * block.specific_force_up_m_s2;
      if (acc.imu_frames != acc.frames && result.has_imu) {
        ++result.blocks_without_attitude;
        ++without_attitude;
      } else if (rejectedOutside(block, config.domain, motors)) {
        ++result.blocks_rejected_outside;
        ++rejected;
      } else {
        result.blocks.push_back(block);
        ++usable;
      }
      ++block_in_segment;
      acc = Accumulator();
    };

    for (const RcOutFrame& frame : commands) {
      if (frame.time_s < segment.start_s) continue;
      if (frame.time_s > segment.end_s) break;
      const int index = static_cast<int>((frame.time_s - segment.start_s) / config.block_s);
      if (index != current_block) {
        flush();
        current_block = index;
      }
      ++frames;
      const BatteryReading* b = battery.at(frame.time_s, timeout);
      if (!b || !(b->voltage_v > 0.0)) {
        ++without_battery;
        continue;
      }
      ++acc.frames;
      if (acc.frames == 1) acc.first_time = frame.time_s;
      acc.last_time = frame.time_s;
      acc.time += frame.time_s;
      acc.voltage += b->voltage_v;
      const ImuReading* i = imu.at(frame.time_s, timeout);
      // The node's preparation of the effects' signals (effect_signals.h), frame by frame.
      const effects::Signals prepared = effects::prepareSignals(signals.at(frame.time_s, timeout, *b, i));
      if (std::isfinite(prepared.value(effects::Signal::kBatteryCurrent))) {
        acc.current += prepared.value(effects::Signal::kBatteryCurrent);
        ++acc.current_frames;
      }
      acc.addMotors(frame, motors, vehicle, i, esc.at(frame.time_s, timeout));
      if (i) {
        acc.force_up += (i->orientation * i->specific_force_m_s2).z();
        ++acc.imu_frames;
      }
      acc.addSignals(prepared);
      const ScalarReading* z = altitude.at(frame.time_s, timeout);
      if (z) {
        acc.altitude += z->value;
        ++acc.altitude_frames;
      }
    }
    flush();
    group += (block_in_segment + blocks_per_group - 1) / blocks_per_group;
    result.frames_without_battery += without_battery;
    // Blocks a rejecting model refuses are said once for all flights (the diagnosis' count).
    if (usable == 0 && rejected == 0) {
      result.skipped.push_back(nothingInSegment(segmentName(flight, s), without_attitude, frames, without_battery,
                                                timeout));
    }
  }
  return result;
}

}  // namespace gap
}  // namespace propulsion_estimator
