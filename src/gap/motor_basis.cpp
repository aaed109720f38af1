#include "propulsion_estimator/gap/motor_basis.h"

namespace propulsion_estimator {
namespace gap {

const char* motorBasisName(MotorBasis basis) {
  switch (basis) {
    case MotorBasis::kNone: return "none";
    case MotorBasis::kPayloads: return "payloads";
    case MotorBasis::kReference: return "reference";
    case MotorBasis::kIdeal: break;
  }
  return "ideal";
}

const char* motorBasisAgainst(MotorBasis basis) {
  switch (basis) {
    case MotorBasis::kNone: return "nothing";
    case MotorBasis::kPayloads: return "the weighed payloads";
    case MotorBasis::kReference: return "the vehicle's healthy flights";
    case MotorBasis::kIdeal: break;
  }
  return "the ideal balance";
}

}  // namespace gap
}  // namespace propulsion_estimator
