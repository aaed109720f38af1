#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {

/// How the motors' model thrusts are judged in steady hover: averaged into blocks of block_s of
/// hover, the newest window_s of such blocks judged together; a motor is flagged when it would
/// lack more than max_gap of its modelled thrust for the yaw balance to hold, and more than three
/// standard errors.
struct MotorHealthConfig {
  double block_s = 1.0;    ///< s
  double window_s = 10.0;  ///< s of steady hover; a whole number of blocks, at least three
  double max_gap = 0.05;   ///< share of the motor's modelled thrust

  /// FieldError naming `capability/motor_health/<field>`.
  void validate() const;
};

/// One motor's standing against the moment balance: its channel (1-based), the share of its
/// modelled thrust it would lack for the balance to hold (positive: weaker than modelled) and
/// that share's standard error.
struct MotorBalanceGap {
  int channel = 0;  ///< RCOut channel, 1-based
  double thrust_gap = 0.0;  ///< share of the modelled thrust missing, positive when weaker than modelled
  double thrust_gap_std = 0.0;  ///< its standard error
};

/// What the motor balance says after the newest steady-hover window; `judged` false (and
/// `unavailable` saying why) until a window is full or without rotor geometry.
struct MotorHealthVerdict {
  bool judged = false;  ///< whether a full window was judged
  std::string unavailable;  ///< why not, when judged is false
  int blocks = 0;  ///< steady-hover blocks in the window
  double yaw_imbalance = 0.0;      ///< sum(s_k T_k) / sum(T_k) over the window (rotor_balance.h)
  double yaw_imbalance_std = 0.0;  ///< its standard error
  std::vector<MotorBalanceGap> motors;  ///< one per motor, in rotor order
  int flagged_channel = 0;  ///< 0: none
  /// The centre of gravity the thrusts balance about, less the URDF's, in m (body x, y): a
  /// centre-of-gravity offset moves every share consistently and is no motor fault. With a motor
  /// flagged, the centre its corrected thrust gives.
  ///@{
  double cg_offset_x_m = 0.0;
  double cg_offset_y_m = 0.0;
  ///@}
};

/// Propulsion health from the moment balance of steady hover (vehicle/rotor_balance.h): a motor
/// whose model thrust stays off the yaw balance is flagged with its channel; of the motors that
/// could explain the imbalance (weaker than modelled), the one whose corrected thrust centre
/// lies nearest the URDF's centre of gravity, as the offline gap diagnosis chooses.
class MotorHealth {
 public:
  /// Throws FieldError for a bad config; `channels` in rotor order.
  MotorHealth(Vehicle vehicle, std::vector<int> channels, MotorHealthConfig config);

  /// One accepted RCOut message's estimate; allocates nothing. A stamp older than the previous one
  /// (a bag restarted) forgets everything.
  void add(const EstimatorOutput& output);
  /// Forgets the blocks (~reset).
  void clear();
  MotorHealthVerdict verdict() const;  ///< the newest window's verdict

  /// As validated.
  const MotorHealthConfig& config() const { return config_; }

 private:
  Vehicle vehicle_;
  std::vector<int> channels_;
  MotorHealthConfig config_;
  std::size_t window_blocks_;
  /// The block being filled: per-motor thrust sums over its samples.
  std::vector<double> block_sums_;
  int block_samples_ = 0;
  double block_start_s_ = 0.0;
  double last_stamp_s_ = 0.0;
  /// Completed blocks' mean thrusts, a ring of window_blocks_ rows.
  std::vector<std::vector<double>> blocks_;
  std::size_t next_block_ = 0;
  std::size_t block_count_ = 0;
};

}  // namespace propulsion_estimator
