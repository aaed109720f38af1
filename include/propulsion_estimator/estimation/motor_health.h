#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/model/motor_reference.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {

/// How the motors' model thrusts are judged in steady hover: averaged into blocks of block_s of
/// hover, the newest window_s of such blocks judged together (estimation/motor_change.h). With the
/// model's motor reference a motor is flagged when it lacks more than max_gap of its thrust against
/// the vehicle's healthy flights, and more than three standard errors of their spread; without one,
/// when it lacks more than max_gap and three times healthy_gap_std against the ideal balance.
struct MotorHealthConfig {
  double block_s = 1.0;    ///< s
  double window_s = 10.0;  ///< s of steady hover; a whole number of blocks, at least three
  double max_gap = 0.05;   ///< share of the motor's modelled thrust
  /// Without a reference: the spread of the gap healthy vehicles show against the ideal balance
  /// (gap::DiagnosisConfig::motor_healthy_gap_std, where it is calibrated).
  double healthy_gap_std = 0.067;

  /// FieldError naming `capability/motor_health/<field>`.
  void validate() const;
};

/// One motor's standing against the moment balance: its channel (1-based), the share of its
/// modelled thrust it lacks against the reference or the ideal balance (positive: weaker) and that
/// share's standard error.
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
  double yaw_imbalance = kNaN;      ///< sum(s_k T_k) / sum(T_k) over the window (rotor_balance.h); NaN unjudged
  double yaw_imbalance_std = kNaN;  ///< its standard error
  std::vector<MotorBalanceGap> motors;  ///< one per motor, in rotor order
  int flagged_channel = 0;  ///< 0: none
  /// The centre of the window's model thrusts, less the URDF's centre of gravity, in m (body x, y):
  /// a centre-of-gravity offset moves every share consistently and is no motor fault. NaN unjudged.
  ///@{
  double cg_offset_x_m = kNaN;
  double cg_offset_y_m = kNaN;
  ///@}
};

/// Propulsion health from the moment balance of steady hover (estimation/motor_change.h): each
/// motor's share of the summed model thrust over the newest window, judged against the vehicle's
/// healthy reference where the model carries one (a whole window counts as one flight against
/// the reference's flight-to-flight spread), else against the ideal balance beyond the spread
/// healthy vehicles show, as the offline gap diagnosis judges.
class MotorHealth {
 public:
  /// Throws FieldError for a bad config or reference; `channels` in rotor order; `reference`: the
  /// model's motorReference(), with one share per rotor.
  MotorHealth(Vehicle vehicle, std::vector<int> channels, MotorHealthConfig config,
              std::optional<MotorReference> reference = std::nullopt);

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
  std::optional<MotorReference> reference_;
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
