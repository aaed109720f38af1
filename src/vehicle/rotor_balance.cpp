#include "propulsion_estimator/vehicle/rotor_balance.h"

namespace propulsion_estimator {
namespace {

double sum(const std::vector<double>& values) {
  double total = 0.0;
  for (double v : values) total += v;
  return total;
}

}  // namespace

double yawImbalance(const Vehicle& vehicle, const std::vector<double>& thrust_n) {
  double spin = 0.0;
  for (std::size_t k = 0; k < thrust_n.size(); ++k) spin += vehicle.rotors[k].spin_direction * thrust_n[k];
  return spin / sum(thrust_n);
}

Eigen::Vector2d thrustCentre(const Vehicle& vehicle, const std::vector<double>& thrust_n) {
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < thrust_n.size(); ++k) moment += thrust_n[k] * vehicle.rotors[k].position_m.head<2>();
  return moment / sum(thrust_n);
}

}  // namespace propulsion_estimator
