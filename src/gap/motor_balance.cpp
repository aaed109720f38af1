#include "propulsion_estimator/gap/motor_balance.h"

#include <cmath>
#include <functional>
#include <limits>
#include <map>

#include "propulsion_estimator/vehicle/rotor_balance.h"

namespace propulsion_estimator {
namespace gap {
namespace {

// Payloads this much apart move the centre of gravity enough to tell the hypotheses apart.
constexpr double kMinPayloadSpreadKg = 0.05;
// Segments with fewer steady-hover blocks than this give too noisy a moment.
constexpr int kMinSegmentBlocks = 6;

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
  // The spread over segments of the empty vehicle's mass moment, if motor j gives (1 - gap) of
  // its modelled thrust.
  const auto moment_spread = [&](int j, double gap) {
    std::vector<Eigen::Vector2d> moments;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& [key, entry] : segment_sums) {
      const auto& [sums, count] = entry;
      if (count < kMinSegmentBlocks) continue;
      std::vector<double> corrected(motors);
      for (int k = 0; k < motors; ++k) corrected[k] = sums[k] / count * (k == j ? 1.0 - gap : 1.0);
      moments.push_back(segment_mass.at(key) * thrustCentre(vehicle, corrected));
      mean += moments.back();
    }
    if (moments.size() < 2) return std::numeric_limits<double>::infinity();
    mean /= moments.size();
    double spread = 0.0;
    for (const Eigen::Vector2d& m : moments) spread += (m - mean).squaredNorm() / moments.size();
    return std::sqrt(spread);
  };

  double best_distance = std::numeric_limits<double>::infinity();
  int best = -1;
  for (int j = 0; j < motors; ++j) {
    const double gap = weakMotorGap(vehicle, mean_thrust, yaw_mean, j);
    const double ci = std::abs(gap) * (std::abs(yaw_mean) > 0.0 ? yaw_ci / std::abs(yaw_mean) : 0.0);
    balance.motors.push_back({channels[j], 100.0 * gap, 100.0 * ci});
    const double distance =
        payloads_differ ? moment_spread(j, gap) : (impliedCentre(vehicle, mean_thrust, j, gap) - prior).norm();
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
