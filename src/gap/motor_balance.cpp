#include "propulsion_estimator/gap/motor_balance.h"

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "diagnoser.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/gap/model_check_replay.h"
#include "propulsion_estimator/vehicle/rotor_balance.h"

namespace propulsion_estimator {
namespace gap {
namespace {

// Payloads this much apart move the centre of gravity enough to tell the hypotheses apart.
constexpr double kMinPayloadSpreadKg = 0.05;
// Segments with fewer steady-hover blocks than this give too noisy a moment.
constexpr int kMinSegmentBlocks = 6;
// A gap found from the moments is sought within 0..kMaxGap in steps of kGapStep, on this many
// segments or more (the jackknife needs a few).
constexpr double kMaxGap = 0.35;
constexpr double kGapStep = 0.0025;
constexpr int kMinMomentSegments = 3;

// Each motor's summed model thrust and the block count over the steady-hover blocks sharing a key.
using ThrustSums = std::map<std::pair<int, int>, std::pair<std::vector<double>, int>>;

ThrustSums sumHoverThrusts(const ThrustViews& views, const std::vector<Block>& blocks,
                           const std::function<std::pair<int, int>(const Block&)>& key) {
  ThrustSums sums_by_key;
  for (const Block& block : blocks) {
    if (!block.hover) continue;
    auto& [sums, count] = sums_by_key[key(block)];
    sums.resize(views.motors(), 0.0);
    for (int k = 0; k < views.motors(); ++k) sums[k] += views.motorThrust(block.pwm_us[k], block.voltage_v);
    ++count;
  }
  return sums_by_key;
}

// The empty vehicle's mass moment per weighed segment of steady hover (payloads hang below
// base_link's origin, so it is the same in every segment), under the hypothesis that one motor
// gives less than its modelled thrust.
class SegmentMoments {
 public:
  SegmentMoments(const Vehicle& vehicle, const ThrustSums& sums, const std::map<std::pair<int, int>, double>& mass,
                 int motors)
      : vehicle_(vehicle), sums_(sums), mass_(mass), motors_(motors) {
    for (const auto& entry : sums_) segments_ += entry.second.second >= kMinSegmentBlocks ? 1 : 0;
  }

  int segments() const { return segments_; }

  // The spread over the segments (but `skip`) of the moment, in kg m, if motor j gives (1 - gap)
  // of its modelled thrust.
  double spread(int j, double gap, int skip = -1) const {
    std::vector<Eigen::Vector2d> moments;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    int index = -1;
    for (const auto& [key, entry] : sums_) {
      const auto& [sums, count] = entry;
      if (count < kMinSegmentBlocks || ++index == skip) continue;
      std::vector<double> corrected(motors_);
      for (int k = 0; k < motors_; ++k) corrected[k] = sums[k] / count * (k == j ? 1.0 - gap : 1.0);
      moments.push_back(mass_.at(key) * thrustCentre(vehicle_, corrected));
      mean += moments.back();
    }
    if (moments.size() < 2) return std::numeric_limits<double>::infinity();
    mean /= moments.size();
    double spread = 0.0;
    for (const Eigen::Vector2d& m : moments) spread += (m - mean).squaredNorm() / moments.size();
    return std::sqrt(spread);
  }

  // Motor j's gap that keeps the moment most constant, within 0..kMaxGap, and its 95 % half-width
  // by the jackknife over the segments. A propeller that lost thrust but kept its torque (worn,
  // bent) leaves the yaw balance as it was and shows here only.
  std::pair<double, double> gap(int j) const {
    const double fitted = bestGap(j, -1);
    std::vector<double> left_out;
    double mean = 0.0;
    for (int s = 0; s < segments_; ++s) {
      left_out.push_back(bestGap(j, s));
      mean += left_out.back() / segments_;
    }
    double variance = 0.0;
    for (double g : left_out) variance += (g - mean) * (g - mean) * (segments_ - 1.0) / segments_;
    return {fitted, 1.96 * std::sqrt(variance)};
  }

 private:
  // The grid's best step, refined by the parabola through it and its neighbours: a gap quantised
  // to the grid would give every jackknife replicate the same step and a zero interval. A best
  // step on either end of the grid stays there (a fit resting on its bound).
  double bestGap(int j, int skip) const {
    const int steps = static_cast<int>(std::round(kMaxGap / kGapStep));
    int best = 0;
    double least = std::numeric_limits<double>::infinity();
    for (int step = 0; step <= steps; ++step) {
      const double value = spread(j, step * kGapStep, skip);
      if (value < least) {
        least = value;
        best = step;
      }
    }
    if (best == 0 || best == steps) return best * kGapStep;
    // The moments are linear in the gap, so their variance (the spread squared) is a parabola.
    const double below = std::pow(spread(j, (best - 1) * kGapStep, skip), 2);
    const double above = std::pow(spread(j, (best + 1) * kGapStep, skip), 2);
    const double curvature = below - 2.0 * least * least + above;
    const double shift = curvature > 0.0 ? 0.5 * (below - above) / curvature : 0.0;
    return (best + shift) * kGapStep;
  }

  const Vehicle& vehicle_;
  const ThrustSums& sums_;
  const std::map<std::pair<int, int>, double>& mass_;
  int motors_;
  int segments_ = 0;
};

// Each unit's mean model thrust per motor over its steady hover: each flight; with `stretches`
// and a single flight, each stretch (group) of it. Against a reference the units must be flights:
// the stretches of one flight share its offset, which only the reference's flight-to-flight
// spread measures.
std::vector<HoverThrusts> hoverUnits(const ThrustViews& views, const std::vector<Block>& blocks, bool stretches) {
  std::set<int> flights;
  for (const Block& block : blocks) {
    if (block.hover) flights.insert(block.flight);
  }
  const bool by_flight = flights.size() >= 2 || !stretches;
  const ThrustSums sums = sumHoverThrusts(views, blocks, [by_flight](const Block& block) {
    return std::make_pair(block.flight, by_flight ? 0 : block.group);
  });
  std::vector<HoverThrusts> units;
  for (const auto& entry : sums) {
    const auto& [thrust, count] = entry.second;
    units.emplace_back();
    for (double t : thrust) units.back().push_back(t / count);
  }
  return units;
}

// The judgement of the shares, as the report's table holds it (%, 95 % half-widths).
void takeVerdict(const MotorChangeVerdict& verdict, const std::vector<int>& channels, MotorBalance* balance) {
  for (std::size_t j = 0; j < verdict.motors.size(); ++j) {
    balance->motors.push_back(
        {channels[j], 100.0 * verdict.motors[j].gap, 100.0 * 1.96 * verdict.motors[j].gap_std});
  }
  if (verdict.suspect >= 0) balance->suspect_channel = channels[verdict.suspect];
  if (!verdict.unavailable.empty()) balance->unavailable = verdict.unavailable;
}

// The moments across weighed payloads: motor j's gap that keeps the empty vehicle's mass moment
// the same in every segment. The one whose gap does so best is the candidate; a gap resting on
// the search's bounds or without an interval says nothing about which motor it is. Healthy parts
// differ by a few per cent and a payload hung a millimetre off the hook moves a motor's gap by
// about as much, so without a reference the candidate must also stand beyond the healthy spread
// (`healthy_gap_std`, three of it), as on the ideal balance.
void balanceByMoments(const SegmentMoments& moments, const std::vector<int>& channels, double min_gap,
                      double healthy_gap_std, MotorBalance* balance) {
  double best_spread = std::numeric_limits<double>::infinity();
  int best = -1;
  for (int j = 0; j < static_cast<int>(channels.size()); ++j) {
    const auto [gap, ci] = moments.gap(j);
    balance->motors.push_back({channels[j], 100.0 * gap, 100.0 * ci});
    const double spread = moments.spread(j, gap);
    if (gap > 0.0 && spread < best_spread) {
      best_spread = spread;
      best = j;
    }
  }
  if (best < 0) return;
  const MotorGap& candidate = balance->motors[best];
  const double gap = candidate.thrust_gap_pct / 100.0;
  const bool on_bound = gap < kGapStep / 2 || gap > kMaxGap - kGapStep / 2;
  // ci_pct is a 95 % half-width, about two standard errors: three standard errors are 1.5 of it.
  if (!on_bound && candidate.ci_pct > 0.0 && gap > min_gap && gap > 3.0 * healthy_gap_std &&
      candidate.thrust_gap_pct > 1.5 * candidate.ci_pct) {
    balance->suspect_channel = candidate.channel;
  }
}

}  // namespace

MotorBalance balanceMotors(const ThrustViews& views, const Vehicle& vehicle, const std::vector<Block>& blocks,
                           const std::vector<int>& channels, const DiagnosisConfig& config) {
  MotorBalance balance;
  const int motors = views.motors();
  if (!vehicle.hasGeometry()) {
    balance.unavailable = "no rotor geometry (give --urdf)";
    return balance;
  }
  if (motors < 4) {
    balance.unavailable = "fewer than four motors";
    return balance;
  }
  const ThrustSums groups =
      sumHoverThrusts(views, blocks, [](const Block& block) { return std::make_pair(block.flight, block.group); });
  if (groups.size() < 3) {
    balance.unavailable = "fewer than three stretches of steady hover";
    return balance;
  }
  std::vector<double> mean_thrust(motors, 0.0);
  for (const auto& entry : groups) {
    const auto& [sums, count] = entry.second;
    for (int k = 0; k < motors; ++k) mean_thrust[k] += sums[k] / count / groups.size();
  }
  const Eigen::Vector2d centre = thrustCentre(vehicle, mean_thrust);
  balance.cg_offset_x_m = centre.x();
  balance.cg_offset_y_m = centre.y();

  MotorChangeRule rule;
  rule.min_gap = config.motor_min_gap;
  rule.healthy_gap_std = config.motor_healthy_gap_std;
  if (config.motor_reference) {
    balance.basis = MotorBasis::kReference;
    takeVerdict(judgeAgainstReference(vehicle, *config.motor_reference, hoverUnits(views, blocks, false), rule), channels,
                &balance);
    return balance;
  }
  // Per weighed segment of steady hover: its mass and each motor's mean model thrust. A payload
  // hangs below base_link's origin, so the empty vehicle's mass moment about that origin,
  // mass x centre of gravity, is the same in every segment: the hypothesis that keeps it
  // constant across payloads is the one that holds, whatever the empty centre of gravity.
  const ThrustSums segment_sums =
      sumHoverThrusts(views, blocks, [](const Block& block) { return std::make_pair(block.flight, block.segment); });
  std::map<std::pair<int, int>, double> segment_mass;
  for (const Block& block : blocks) {
    if (block.hover) segment_mass[{block.flight, block.segment}] = block.mass_kg;
  }
  double lightest = std::numeric_limits<double>::infinity(), heaviest = 0.0;
  for (const auto& entry : segment_mass) {
    lightest = std::min(lightest, entry.second);
    heaviest = std::max(heaviest, entry.second);
  }
  const SegmentMoments moments{vehicle, segment_sums, segment_mass, motors};
  if (heaviest - lightest > kMinPayloadSpreadKg && moments.segments() >= kMinMomentSegments) {
    balance.basis = MotorBasis::kPayloads;
    balance.healthy_gap_std_pct = 100.0 * config.motor_healthy_gap_std;
    balanceByMoments(moments, channels, config.motor_min_gap, config.motor_healthy_gap_std, &balance);
    return balance;
  }
  balance.basis = MotorBasis::kIdeal;
  balance.healthy_gap_std_pct = 100.0 * config.motor_healthy_gap_std;
  takeVerdict(judgeAgainstIdeal(vehicle, hoverUnits(views, blocks, true), rule), channels, &balance);
  return balance;
}

namespace {

// The healthy vehicle's weighed vertical thrust over each view's, summed over its steady blocks
// (NaN for a view no block has), and the air and motor temperature those blocks flew in.
void learnThrustFactors(const ThrustViews& views, const std::vector<Block>& blocks, MotorReference* reference) {
  const effects::ModelEffects none;
  const auto factor = [&blocks](const std::function<double(const Block&)>& view) {
    double truth = 0.0, modelled = 0.0;
    for (const Block& block : blocks) {
      const double thrust = view(block);
      if (!std::isfinite(thrust) || !(block.truth_n > 0.0)) continue;
      truth += block.truth_n;
      modelled += thrust;
    }
    return modelled > 0.0 ? truth / modelled : std::numeric_limits<double>::quiet_NaN();
  };
  reference->thrust_factor = factor([&](const Block& block) { return views.pwmView(block, none); });
  reference->current_thrust_factor = factor([&](const Block& block) { return views.currentView(block, none); });
  reference->rpm_thrust_factor = factor([&](const Block& block) { return views.rpmView(block, none); });
  const auto mean_signal = [&blocks](effects::Signal signal) {
    double sum = 0.0;
    int count = 0;
    for (const Block& block : blocks) {
      const double value = block.signals.value(signal);
      if (!std::isfinite(value) || !(block.truth_n > 0.0)) continue;
      sum += value;
      ++count;
    }
    return count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
  };
  reference->air_density_kg_m3 = mean_signal(effects::Signal::kAirDensity);
  reference->motor_temperature_c = mean_signal(effects::Signal::kMotorTemperature);
}

// What the live ESC check sees of each healthy motor: the mean over the flights of each flight's
// mean deviations, judged against the other motors alone. Left empty unless every flight was
// judged: a baseline from some flights would judge the others' motors against too little.
void learnEscBaseline(const PropulsionModel& model, const Vehicle& vehicle, const std::vector<Flight>& flights,
                      MotorReference* reference) {
  PropulsionModel plain = model;
  plain.setMotorReference(std::nullopt);
  const std::size_t motors = vehicle.rotors.size();
  std::vector<double> rpm(motors, 0.0), current(motors, 0.0);
  double level = 0.0;
  for (const Flight& flight : flights) {
    const ModelCheckReplay replay = replayModelCheck(plain, vehicle, flight.streams);
    if (replay.rpm_deviation.size() != motors) return;
    level += replay.median_rpm_ratio / static_cast<double>(flights.size());
    for (std::size_t k = 0; k < motors; ++k) {
      rpm[k] += replay.rpm_deviation[k] / static_cast<double>(flights.size());
      current[k] += replay.current_deviation[k] / static_cast<double>(flights.size());
    }
  }
  reference->esc_rpm_deviation = rpm;
  reference->esc_current_deviation = current;
  reference->esc_rpm_level = level;
}

}  // namespace

MotorReference learnReference(const PropulsionModel& model, const Vehicle& vehicle, const std::vector<Flight>& flights,
                              const DiagnosisConfig& config) {
  if (!vehicle.hasGeometry()) throw ConfigError("--reference: needs the rotor geometry (give --urdf or --frame)");
  const int motors = static_cast<int>(vehicle.rotors.size());
  const ThrustViews views(model, motors, false);
  const BlockConfig block_config = detail::blockConfig(config, model, motors, 0.0);
  std::vector<Block> blocks;
  for (int f = 0; f < static_cast<int>(flights.size()); ++f) {
    for (const Block& block : cutIntoBlocks(flights[f], f, vehicle, block_config, 0).blocks) {
      if (isQuasiSteady(block, config.max_pwm_change_us, config.max_accel_m_s2)) blocks.push_back(block);
    }
  }
  std::set<int> with_hover;
  for (const Block& block : blocks) {
    if (block.hover) with_hover.insert(block.flight);
  }
  if (with_hover.size() < 3) {
    throw ConfigError("--reference: steady hover on " + std::to_string(with_hover.size()) + " of " +
                      std::to_string(flights.size()) + " flights; a reference needs at least 3");
  }
  MotorReference reference = learnMotorReference(vehicle, hoverUnits(views, blocks, false));
  learnThrustFactors(ThrustViews(model, motors, true), blocks, &reference);
  learnEscBaseline(model, vehicle, flights, &reference);
  return reference;
}

}  // namespace gap
}  // namespace propulsion_estimator
