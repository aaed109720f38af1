#pragma once

#include <vector>

#include "propulsion_estimator/gap/blocks.h"
#include "propulsion_estimator/gap/diagnosis.h"
#include "propulsion_estimator/gap/thrust_views.h"
#include "propulsion_estimator/vehicle/vehicle.h"

namespace propulsion_estimator {
namespace gap {

/// Which motor's model is off, from the moment balance of steady hover.
///
/// In steady hover the rotors' drag torques cancel (yaw) and the thrusts balance about the
/// centre of gravity (roll, pitch). A centre of gravity away from the URDF's only moves the roll
/// and pitch balance, so the model's thrusts still cancel in yaw, sum(s_k T_k) = 0 (s_k the spin
/// direction, torque proportional to thrust for identical propellers). A motor whose model reads
/// high by a fraction e_j breaks the yaw balance by s_j T_j e_j. On a quad the yaw residual fixes
/// e_j up to which motor of that spin direction (or which of the other, reading low) it is. Only
/// motors reading high (weaker than modelled: a damaged propeller, a worn motor) are candidates.
/// With payloads of different masses (hanging below base_link's origin) each motor's gap is the
/// one that keeps the empty vehicle's mass moment the same in every segment (its uncertainty by
/// the jackknife over segments), and the motor whose gap does so best is taken: a worn or bent
/// propeller, which keeps its torque, leaves the yaw balance as it was and shows only there. With
/// one mass the gap is the yaw's, and the motor the one whose implied centre of gravity lies
/// nearest the URDF's. A motor is a suspect only when its gap exceeds `min_gap` and three times
/// its uncertainty.
MotorBalance balanceMotors(const ThrustViews& views, const Vehicle& vehicle, const std::vector<Block>& blocks,
                           const std::vector<int>& channels, double min_gap);

}  // namespace gap
}  // namespace propulsion_estimator
