#include "propulsion_estimator/estimation/motor_health.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/estimation/motor_change.h"
#include "propulsion_estimator/vehicle/rotor_balance.h"

namespace propulsion_estimator {
void MotorHealthConfig::validate() const {
  requirePositive("capability/motor_health/block_s", block_s);
  requirePositive("capability/motor_health/window_s", window_s);
  requireWithin("capability/motor_health/max_gap", max_gap, 0.0, 1.0);
  requireWithin("capability/motor_health/healthy_gap_std", healthy_gap_std, 0.0, 1.0);
  const double blocks = window_s / block_s;
  if (std::abs(blocks - std::round(blocks)) > 1e-9 || std::round(blocks) < 3.0) {
    throw FieldError("capability/motor_health/window_s",
                     formatNumber(window_s) + " s is not a whole number of at least three blocks of block_s " +
                         formatNumber(block_s) + " s");
  }
}

MotorHealth::MotorHealth(Vehicle vehicle, std::vector<int> channels, MotorHealthConfig config,
                         std::optional<MotorReference> reference)
    : vehicle_(std::move(vehicle)), channels_(std::move(channels)), config_(config), reference_(std::move(reference)) {
  config_.validate();
  if (reference_) {
    reference_->validate();
    if (reference_->shares.size() != vehicle_.rotors.size()) {
      throw FieldError("motor_reference.shares", std::to_string(reference_->shares.size()) + " shares for " +
                                                     std::to_string(vehicle_.rotors.size()) + " rotors");
    }
  }
  window_blocks_ = static_cast<std::size_t>(std::round(config_.window_s / config_.block_s));
  block_sums_.assign(vehicle_.rotors.size(), 0.0);
  blocks_.assign(window_blocks_, std::vector<double>(vehicle_.rotors.size(), 0.0));
}

void MotorHealth::clear() {
  block_samples_ = 0;
  block_count_ = 0;
  next_block_ = 0;
}

void MotorHealth::add(const EstimatorOutput& output) {
  if (output.stamp_s < last_stamp_s_) clear();
  last_stamp_s_ = output.stamp_s;
  // Only steady hover balances its moments; a partial block of a hover that ended is dropped.
  if (!output.hover.hovering || output.motors.size() != block_sums_.size()) {
    block_samples_ = 0;
    return;
  }
  if (block_samples_ == 0) {
    block_start_s_ = output.stamp_s;
    std::fill(block_sums_.begin(), block_sums_.end(), 0.0);
  }
  for (std::size_t k = 0; k < block_sums_.size(); ++k) block_sums_[k] += output.motors[k].estimate.thrust_n;
  ++block_samples_;
  if (output.stamp_s - block_start_s_ < config_.block_s) return;
  std::vector<double>& block = blocks_[next_block_];
  for (std::size_t k = 0; k < block.size(); ++k) block[k] = block_sums_[k] / block_samples_;
  next_block_ = (next_block_ + 1) % window_blocks_;
  block_count_ = std::min(block_count_ + 1, window_blocks_);
  block_samples_ = 0;
}

MotorHealthVerdict MotorHealth::verdict() const {
  MotorHealthVerdict verdict;
  verdict.blocks = static_cast<int>(block_count_);
  const int motors = static_cast<int>(vehicle_.rotors.size());
  if (!vehicle_.hasGeometry()) {
    verdict.unavailable = "no rotor geometry (a URDF is needed)";
    return verdict;
  }
  if (motors < 4) {
    verdict.unavailable = "fewer than four motors";
    return verdict;
  }
  if (block_count_ < window_blocks_) {
    verdict.unavailable = "steady hover " + formatPrintf("%.0f", block_count_ * config_.block_s) + " of " +
                          formatPrintf("%.0f s", config_.window_s);
    return verdict;
  }
  std::vector<double> mean(motors, 0.0);
  std::vector<double> yaw;
  for (const std::vector<double>& block : blocks_) {
    for (int k = 0; k < motors; ++k) mean[k] += block[k] / window_blocks_;
    yaw.push_back(yawImbalance(vehicle_, block));
  }
  double yaw_mean = 0.0, yaw_var = 0.0;
  for (double y : yaw) yaw_mean += y / yaw.size();
  for (double y : yaw) yaw_var += (y - yaw_mean) * (y - yaw_mean) / (yaw.size() - 1);
  const double yaw_std = std::sqrt(yaw_var / yaw.size());
  verdict.judged = true;
  verdict.yaw_imbalance = yaw_mean;
  verdict.yaw_imbalance_std = yaw_std;

  const Eigen::Vector2d prior = vehicle_.empty_mass ? Eigen::Vector2d(vehicle_.empty_mass->centre_of_mass_m.head<2>())
                                                    : Eigen::Vector2d::Zero();
  const Eigen::Vector2d centre = thrustCentre(vehicle_, mean);
  MotorChangeRule rule;
  rule.min_gap = config_.max_gap;
  rule.healthy_gap_std = config_.healthy_gap_std;
  const MotorChangeVerdict change =
      reference_ ? judgeAgainstReference(vehicle_, *reference_, {mean}, rule) : judgeAgainstIdeal(vehicle_, {mean}, rule);
  if (!change.unavailable.empty()) {
    verdict.judged = false;
    verdict.unavailable = change.unavailable;
    return verdict;
  }
  for (int j = 0; j < motors && j < static_cast<int>(change.motors.size()); ++j) {
    verdict.motors.push_back({channels_[j], change.motors[j].gap, change.motors[j].gap_std});
  }
  if (change.suspect >= 0) verdict.flagged_channel = channels_[change.suspect];
  verdict.cg_offset_x_m = centre.x() - prior.x();
  verdict.cg_offset_y_m = centre.y() - prior.y();
  return verdict;
}

}  // namespace propulsion_estimator
