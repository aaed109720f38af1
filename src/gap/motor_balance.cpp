#include "propulsion_estimator/gap/motor_balance.h"

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <utility>

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
  double bestGap(int j, int skip) const {
    double best = 0.0, least = std::numeric_limits<double>::infinity();
    for (int step = 0; step * kGapStep <= kMaxGap + 1e-12; ++step) {
      const double value = spread(j, step * kGapStep, skip);
      if (value < least) {
        least = value;
        best = step * kGapStep;
      }
    }
    return best;
  }

  const Vehicle& vehicle_;
  const ThrustSums& sums_;
  const std::map<std::pair<int, int>, double>& mass_;
  int motors_;
  int segments_ = 0;
};

}  // namespace

MotorBalance balanceMotors(const ThrustViews& views, const Vehicle& vehicle, const std::vector<Block>& blocks,
                           const std::vector<int>& channels, double min_gap) {
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
  // Mean model thrust of each motor, and the yaw residual, per independent group of hover blocks.
  const ThrustSums groups =
      sumHoverThrusts(views, blocks, [](const Block& block) { return std::make_pair(block.flight, block.group); });
  if (groups.size() < 3) {
    balance.unavailable = "fewer than three stretches of steady hover";
    return balance;
  }
  std::vector<double> mean_thrust(motors, 0.0), yaw, thrust(motors);
  for (const auto& entry : groups) {
    const auto& [sums, count] = entry.second;
    for (int k = 0; k < motors; ++k) {
      thrust[k] = sums[k] / count;
      mean_thrust[k] += thrust[k] / groups.size();
    }
    yaw.push_back(yawImbalance(vehicle, thrust));
  }
  double yaw_mean = 0.0;
  for (double y : yaw) yaw_mean += y / yaw.size();
  double yaw_var = 0.0;
  for (double y : yaw) yaw_var += (y - yaw_mean) * (y - yaw_mean) / (yaw.size() - 1);
  const double yaw_ci = 1.96 * std::sqrt(yaw_var / yaw.size());

  const Eigen::Vector2d centre = thrustCentre(vehicle, mean_thrust);
  balance.cg_offset_x_m = centre.x();
  balance.cg_offset_y_m = centre.y();
  const Eigen::Vector2d prior =
      vehicle.empty_mass ? Eigen::Vector2d(vehicle.empty_mass->centre_of_mass_m.head<2>()) : Eigen::Vector2d::Zero();

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
  const bool payloads_differ = heaviest - lightest > kMinPayloadSpreadKg;
  const SegmentMoments moments{vehicle, segment_sums, segment_mass, motors};
  const bool by_moment = payloads_differ && moments.segments() >= kMinMomentSegments;

  double best_distance = std::numeric_limits<double>::infinity();
  int best = -1;
  // Motor j's gap and its 95 % half-width: from the moments, else from the yaw residual.
  const auto gap_of = [&](int j) -> std::pair<double, double> {
    if (by_moment) return moments.gap(j);
    const double gap = weakMotorGap(vehicle, mean_thrust, yaw_mean, j);
    return {gap, std::abs(gap) * (std::abs(yaw_mean) > 0.0 ? yaw_ci / std::abs(yaw_mean) : 0.0)};
  };
  for (int j = 0; j < motors; ++j) {
    const auto [gap, ci] = gap_of(j);
    balance.motors.push_back({channels[j], 100.0 * gap, 100.0 * ci});
    const double distance =
        payloads_differ ? moments.spread(j, gap) : (impliedCentre(vehicle, mean_thrust, j, gap) - prior).norm();
    // A yaw imbalance is explained as well by one motor weaker than modelled as by its
    // neighbour of the other spin direction stronger: the failures that happen (a chipped,
    // bent or wrong propeller, a worn motor or bearing) give less thrust, never more.
    if (gap > 0.0 && distance < best_distance) {
      best_distance = distance;
      best = j;
    }
  }
  if (best < 0) return balance;
  const MotorGap& candidate = balance.motors[best];
  // ci_pct is a 95 % half-width, about two standard errors: three standard errors are 1.5 of it.
  if (std::abs(candidate.thrust_gap_pct) > 100.0 * min_gap && std::abs(candidate.thrust_gap_pct) > 1.5 * candidate.ci_pct) {
    balance.suspect_channel = candidate.channel;
  }
  return balance;
}

}  // namespace gap
}  // namespace propulsion_estimator
