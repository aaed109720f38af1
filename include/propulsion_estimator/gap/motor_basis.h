#pragma once

namespace propulsion_estimator {
namespace gap {

/// What the motor balance judged each motor against (MotorBalance::basis; balanceMotors() says
/// when each is taken).
enum class MotorBasis {
  kNone,       ///< no balance was made (MotorBalance::unavailable says why)
  kIdeal,      ///< the balance of identical rotors
  kPayloads,   ///< the mass moments across weighed payloads
  kReference,  ///< the vehicle's own healthy flights (--reference)
};

/// "none", "ideal", "payloads" or "reference": its name in report.yaml (motor_basis). Throws
/// nothing.
const char* motorBasisName(MotorBasis basis);
/// "the ideal balance", "the weighed payloads" or "the vehicle's healthy flights" ("nothing" for
/// kNone): what a motor's gap is measured against, for a sentence. Throws nothing.
const char* motorBasisAgainst(MotorBasis basis);

}  // namespace gap
}  // namespace propulsion_estimator
