#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/model/motor_reference.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {

/// Judging each motor by the share of the summed model thrust it carries in steady hover.
///
/// A vehicle's rotors differ from part to part, and clockwise and counter-clockwise propellers are
/// not mirror images: on a healthy vehicle the shares are never the model's ideal ones (on the real
/// Crazyflies of test/data/crazypad the diagonal pair of one spin direction carries 4-5 points more
/// than the other on every flight). A weak rotor j (less thrust than modelled at its PWM) makes the
/// autopilot raise its command until the moments balance again, so its share grows by a fraction
/// e of itself and every share moves by s_k (delta_jk - s_j) e. The thrusts' moments about the
/// centre of gravity (roll, pitch) say which rotor that is, from where it sits; the yaw balance only
/// which spin direction, and a damaged propeller's drag torque changes it too: the yaw pattern (the
/// spin directions less their part along total thrust, roll and pitch, relative to each share) is
/// taken as a nuisance and fitted beside e. The gap fitted is e / (1 + s_j e), the model's excess
/// over the motor's thrust after the shares are renormalised (0.17 for e = 0.18 on a quad). A change common
/// to all rotors leaves the shares as they were and is never put on one; the diagonal partner of a
/// weak rotor moves the roll and pitch balance the other way (e < 0) and is never a suspect.

/// Each motor's mean model thrust over one unit of steady hover (a flight, a stretch), N, in rotor
/// order.
using HoverThrusts = std::vector<double>;

/// thrust / sum(thrust); empty for a non-positive sum.
std::vector<double> thrustShares(const HoverThrusts& thrust_n);

/// The fingerprint of healthy `flights` (one HoverThrusts each). ConfigError when fewer than 3,
/// when their motor counts differ from each other or from the vehicle's, when one has no positive
/// thrust, or when a rotor's place cannot be told from the yaw balance.
MotorReference learnMotorReference(const Vehicle& vehicle, const std::vector<HoverThrusts>& flights);

/// The shares a vehicle with identical rotors and its centre of gravity at the URDF's (the origin
/// without one) carries: the least change from equal shares that balances roll, pitch and yaw.
std::vector<double> idealShares(const Vehicle& vehicle);

/// One motor's weak-rotor gap against the reference: e / (1 + s_j e), e the model's thrust over the
/// motor's less 1 (see above), fitted with the yaw pattern beside it, and its standard error.
struct RotorChange {
  double gap = 0.0;      ///< e: positive when weaker than the reference
  double gap_std = 0.0;  ///< its standard error (0 when it cannot be said)
};

/// The per-motor judgement of some flights against a reference or the ideal balance.
struct MotorChangeVerdict {
  std::vector<RotorChange> motors;  ///< one per motor, in rotor order
  int suspect = -1;                 ///< 0-based rotor weaker than the reference alone; -1: none
  /// "" when judged; else why no motor can be judged (no geometry, fewer than four motors, a
  /// rotor whose place cannot be told apart from the yaw balance).
  std::string unavailable;
};

/// How the flights' shares are judged.
struct MotorChangeRule {
  double min_gap = 0.05;  ///< a suspect lacks more than this fraction of its thrust ...
  double sigmas = 3.0;    ///< ... and more than this many standard errors
  /// Without a reference: the standard deviation of the gap healthy vehicles show against the
  /// ideal balance (part-to-part spread and a centre of gravity known to a few millimetres); a
  /// suspect must exceed `sigmas` of it.
  double healthy_gap_std = 0.0;
};

/// Judges the units of steady hover `units` (HoverThrusts each, of one vehicle) against
/// `reference`: each motor's gap, the standard error from the reference's flight-to-flight spread
/// and the units' own, and the one motor weaker alone, if any (its gap beyond min_gap and `sigmas`
/// standard errors, the largest such). Needs rotor geometry, at least four motors and a reference of
/// as many motors as the vehicle (else `unavailable` says which).
MotorChangeVerdict judgeAgainstReference(const Vehicle& vehicle, const MotorReference& reference,
                                         const std::vector<HoverThrusts>& units, const MotorChangeRule& rule);

/// Judges `units` without a reference, against idealShares(): a motor is a suspect only beyond
/// the spread healthy vehicles show (rule.healthy_gap_std), as well as min_gap.
MotorChangeVerdict judgeAgainstIdeal(const Vehicle& vehicle, const std::vector<HoverThrusts>& units,
                                     const MotorChangeRule& rule);

}  // namespace propulsion_estimator
