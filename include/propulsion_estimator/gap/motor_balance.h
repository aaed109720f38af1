#pragma once

#include <vector>

#include "propulsion_estimator/gap/blocks.h"
#include "propulsion_estimator/gap/diagnosis.h"
#include "propulsion_estimator/gap/thrust_views.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace gap {

/// Which motor's model is off, from the moment balance of steady hover
/// (estimation/motor_change.h), judged against the best basis the flights give:
/// - `config.motor_reference` given: each motor's change of its share of the summed model thrust
///   from the vehicle's own healthy flights, the yaw pattern fitted beside it as a nuisance (a
///   damaged propeller changes its drag torque too), its uncertainty from the reference's
///   flight-to-flight spread and the flights' own;
/// - else, with payloads of different masses (hanging below base_link's origin) on three weighed
///   segments or more: the gap that keeps the empty vehicle's mass moment the same in every
///   segment, its 95 % interval by the jackknife over segments; a gap resting on its search bound
///   or with a zero interval names no motor, nor one within three of `config.motor_healthy_gap_std`;
/// - else: against the ideal balance of identical rotors, a suspect only beyond three of
///   `config.motor_healthy_gap_std` (the spread healthy vehicles show).
/// A change common to all rotors leaves the shares as they were, and the diagonal partner of a weak
/// rotor moves roll and pitch the other way: neither is ever the suspect. A motor is a suspect only
/// when its gap exceeds `config.motor_min_gap` too. Units: each flight when there are two or more,
/// else each stretch of steady hover.
MotorBalance balanceMotors(const ThrustViews& views, const Vehicle& vehicle, const std::vector<Block>& blocks,
                           const std::vector<int>& channels, const DiagnosisConfig& config);

/// The vehicle's healthy fingerprint from `flights` known to be healthy (their weighed segments),
/// cut into blocks as the diagnosis cuts them (no rotor lag; each flight's ground draw out of the
/// current; the blocks a `reject` model refuses left out) and read in steady hover as the node
/// evaluates `model`. ConfigError when fewer than three flights have steady hover, or for a
/// vehicle without rotor geometry.
MotorReference learnReference(const PropulsionModel& model, const Vehicle& vehicle, const std::vector<Flight>& flights,
                              const DiagnosisConfig& config);

}  // namespace gap
}  // namespace propulsion_estimator
