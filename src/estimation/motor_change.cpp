#include "propulsion_estimator/estimation/motor_change.h"

#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "propulsion_estimator/common/config_error.h"

namespace propulsion_estimator {
namespace {

// A rotor whose own change lies this close to the normalisation and the yaw pattern (relative to
// its length) cannot be told from them.
constexpr double kMinSeparation = 1e-3;

// Rows: total thrust, roll and pitch moments about the centre of gravity (`cg`, m), one column per rotor.
Eigen::MatrixXd forceAndMoments(const Vehicle& vehicle, const Eigen::Vector2d& cg) {
  const int n = static_cast<int>(vehicle.rotors.size());
  Eigen::MatrixXd a(3, n);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d arm = vehicle.rotors[k].position_m.head<2>() - cg;
    a.col(k) << 1.0, arm.x(), arm.y();
  }
  return a;
}

Eigen::Vector2d urdfCentre(const Vehicle& vehicle) {
  return vehicle.empty_mass ? Eigen::Vector2d(vehicle.empty_mass->centre_of_mass_m.head<2>()) : Eigen::Vector2d::Zero();
}

Eigen::VectorXd spins(const Vehicle& vehicle) {
  Eigen::VectorXd s(vehicle.rotors.size());
  for (std::size_t k = 0; k < vehicle.rotors.size(); ++k) s[k] = vehicle.rotors[k].spin_direction;
  return s;
}

// The relative change of each rotor's share (d_k / s_k) fitted as e on rotor j beside the
// normalisation (a constant) and the yaw pattern: a change of drag torque moves the thrusts along
// the part of the spin directions that leaves total thrust, roll and pitch as they were.
class ChangeFit {
 public:
  ChangeFit(const Vehicle& vehicle, const std::vector<double>& reference) : reference_(reference) {
    const int n = static_cast<int>(reference.size());
    const Eigen::MatrixXd a = forceAndMoments(vehicle, urdfCentre(vehicle));
    const Eigen::VectorXd sigma = spins(vehicle);
    // sigma less its projection on the rows of a: the yaw redistribution in thrust, relative to each share.
    const Eigen::VectorXd yaw_thrust = sigma - a.completeOrthogonalDecomposition().solve(a * sigma);
    yaw_ = Eigen::VectorXd(n);
    for (int k = 0; k < n; ++k) yaw_[k] = yaw_thrust[k] / reference[k];
  }

  // e of rotor j for the shares `shares`; NaN when rotor j cannot be told from the nuisances.
  double gap(const std::vector<double>& shares, int j) const {
    const int n = static_cast<int>(reference_.size());
    Eigen::VectorXd relative(n);
    for (int k = 0; k < n; ++k) relative[k] = shares[k] / reference_[k] - 1.0;
    Eigen::MatrixXd x(n, 3);
    x.col(0).setZero();
    x(j, 0) = 1.0;
    x.col(1).setOnes();
    x.col(2) = yaw_;
    // The part of rotor j's own change that the nuisances cannot take up.
    const Eigen::MatrixXd nuisance = x.rightCols(2);
    const Eigen::VectorXd own = x.col(0) - nuisance * nuisance.completeOrthogonalDecomposition().solve(x.col(0));
    if (own.norm() < kMinSeparation) return std::nan("");
    return own.dot(relative) / own.squaredNorm();
  }

 private:
  std::vector<double> reference_;
  Eigen::VectorXd yaw_;
};

std::string geometryProblem(const Vehicle& vehicle) {
  if (!vehicle.hasGeometry()) return "no rotor geometry (give --urdf or --frame)";
  if (vehicle.rotors.size() < 4) return "fewer than four motors";
  return "";
}

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return values.empty() ? 0.0 : sum / values.size();
}

// Sum of squared deviations from the mean.
double scatter(const std::vector<double>& values) {
  const double m = mean(values);
  double sum = 0.0;
  for (double v : values) sum += (v - m) * (v - m);
  return sum;
}

// Each unit's gap of every rotor against `reference`; the verdict's `unavailable` when a rotor
// cannot be told apart.
std::vector<std::vector<double>> unitGaps(const ChangeFit& fit, const std::vector<HoverThrusts>& units, int motors,
                                          std::string* unavailable) {
  std::vector<std::vector<double>> gaps(motors);
  for (const HoverThrusts& unit : units) {
    const std::vector<double> shares = thrustShares(unit);
    if (static_cast<int>(shares.size()) != motors) continue;
    for (int j = 0; j < motors; ++j) {
      const double gap = fit.gap(shares, j);
      if (std::isnan(gap)) {
        *unavailable = "rotor " + std::to_string(j + 1) + "'s place cannot be told from the yaw balance";
        return {};
      }
      gaps[j].push_back(gap);
    }
  }
  return gaps;
}

// The largest gap beyond min_gap and rule.sigmas standard errors (min_gap alone where the standard
// error is zero: parts known alike, a reference without spread), or -1.
int pickSuspect(const std::vector<RotorChange>& motors, const MotorChangeRule& rule) {
  int suspect = -1;
  double best_z = 0.0;
  for (std::size_t j = 0; j < motors.size(); ++j) {
    const RotorChange& m = motors[j];
    if (!(m.gap > rule.min_gap) || m.gap <= rule.sigmas * m.gap_std) continue;
    const double z = m.gap_std > 0.0 ? m.gap / m.gap_std : std::numeric_limits<double>::infinity();
    if (z > best_z) {
      best_z = z;
      suspect = static_cast<int>(j);
    }
  }
  return suspect;
}

}  // namespace

std::vector<double> thrustShares(const HoverThrusts& thrust_n) {
  double sum = 0.0;
  for (double t : thrust_n) sum += t;
  if (!(sum > 0.0)) return {};
  std::vector<double> shares;
  for (double t : thrust_n) shares.push_back(t / sum);
  return shares;
}

std::vector<double> idealShares(const Vehicle& vehicle) {
  const int n = static_cast<int>(vehicle.rotors.size());
  Eigen::MatrixXd a(4, n);
  a.topRows(3) = forceAndMoments(vehicle, urdfCentre(vehicle));
  a.row(3) = spins(vehicle).transpose();
  const Eigen::VectorXd equal = Eigen::VectorXd::Constant(n, 1.0 / n);
  Eigen::Vector4d target(1.0, 0.0, 0.0, 0.0);
  const Eigen::VectorXd shares = equal + a.completeOrthogonalDecomposition().solve(target - a * equal);
  return std::vector<double>(shares.data(), shares.data() + n);
}

MotorReference learnMotorReference(const Vehicle& vehicle, const std::vector<HoverThrusts>& flights) {
  if (static_cast<int>(flights.size()) < kMinReferenceFlights) {
    throw ConfigError("a motor reference needs steady hover on at least " + std::to_string(kMinReferenceFlights) +
                      " healthy flights, got " + std::to_string(flights.size()));
  }
  const std::size_t motors = flights.front().size();
  if (vehicle.hasGeometry() && motors != vehicle.rotors.size()) {
    throw ConfigError("a motor reference's flights have " + std::to_string(motors) + " motors, the vehicle " +
                      std::to_string(vehicle.rotors.size()));
  }
  std::vector<std::vector<double>> shares;
  for (std::size_t i = 0; i < flights.size(); ++i) {
    shares.push_back(thrustShares(flights[i]));
    if (flights[i].size() != motors || shares.back().size() != motors) {
      throw ConfigError("a motor reference's flight " + std::to_string(i + 1) + " has " +
                        std::to_string(flights[i].size()) + " motors against " + std::to_string(motors) +
                        " or no positive model thrust in steady hover");
    }
  }
  const std::size_t n = shares.size();
  MotorReference reference;
  reference.flights = static_cast<int>(n);
  for (std::size_t k = 0; k < motors; ++k) {
    std::vector<double> column;
    for (const auto& s : shares) column.push_back(s[k]);
    reference.shares.push_back(mean(column));
    reference.share_std.push_back(std::sqrt(scatter(column) / (n - 1)));
  }
  reference.gap_std.assign(motors, 0.0);
  if (!geometryProblem(vehicle).empty()) return reference;
  // Each flight against the others' mean: var(e_left_out) = var(e) (1 + 1 / (n - 1)).
  for (std::size_t left = 0; left < n; ++left) {
    std::vector<double> others(motors, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      if (i == left) continue;
      for (std::size_t k = 0; k < motors; ++k) others[k] += shares[i][k] / (n - 1);
    }
    const ChangeFit fit(vehicle, others);
    for (std::size_t j = 0; j < motors; ++j) {
      const double gap = fit.gap(shares[left], static_cast<int>(j));
      if (!std::isfinite(gap)) {
        throw ConfigError("a motor reference: rotor " + std::to_string(j + 1) +
                          "'s place cannot be told from the yaw balance");
      }
      reference.gap_std[j] += gap * gap / n * (n - 1.0) / n;
    }
  }
  for (double& g : reference.gap_std) g = std::sqrt(g);
  return reference;
}

MotorChangeVerdict judgeAgainstReference(const Vehicle& vehicle, const MotorReference& reference,
                                         const std::vector<HoverThrusts>& units, const MotorChangeRule& rule) {
  MotorChangeVerdict verdict;
  verdict.unavailable = geometryProblem(vehicle);
  if (!verdict.unavailable.empty()) return verdict;
  const int motors = static_cast<int>(reference.shares.size());
  if (motors != static_cast<int>(vehicle.rotors.size())) {
    verdict.unavailable = "the reference has " + std::to_string(motors) + " motors, the vehicle " +
                          std::to_string(vehicle.rotors.size());
    return verdict;
  }
  const std::vector<std::vector<double>> gaps =
      unitGaps(ChangeFit(vehicle, reference.shares), units, motors, &verdict.unavailable);
  if (!verdict.unavailable.empty()) return verdict;
  if (gaps.empty() || gaps[0].empty()) {
    verdict.unavailable = "no steady hover with every motor's thrust";
    return verdict;
  }
  const double n_test = gaps[0].size(), n_ref = reference.flights;
  for (int j = 0; j < motors; ++j) {
    // One flight's scatter, pooled from the reference's (n_ref - 1 degrees of freedom) and the
    // judged units' own; the mean's against the reference's mean.
    const double pooled =
        ((n_ref - 1.0) * reference.gap_std[j] * reference.gap_std[j] + scatter(gaps[j])) / (n_ref - 1.0 + n_test - 1.0);
    verdict.motors.push_back({mean(gaps[j]), std::sqrt(pooled * (1.0 / n_test + 1.0 / n_ref))});
  }
  verdict.suspect = pickSuspect(verdict.motors, rule);
  return verdict;
}

MotorChangeVerdict judgeAgainstIdeal(const Vehicle& vehicle, const std::vector<HoverThrusts>& units,
                                     const MotorChangeRule& rule) {
  MotorChangeVerdict verdict;
  verdict.unavailable = geometryProblem(vehicle);
  if (!verdict.unavailable.empty()) return verdict;
  const int motors = static_cast<int>(vehicle.rotors.size());
  const std::vector<std::vector<double>> gaps =
      unitGaps(ChangeFit(vehicle, idealShares(vehicle)), units, motors, &verdict.unavailable);
  if (!verdict.unavailable.empty()) return verdict;
  if (gaps.empty() || gaps[0].empty()) {
    verdict.unavailable = "no steady hover with every motor's thrust";
    return verdict;
  }
  const double n = gaps[0].size();
  for (int j = 0; j < motors; ++j) {
    const double own = n > 1.0 ? scatter(gaps[j]) / (n - 1.0) / n : 0.0;
    verdict.motors.push_back({mean(gaps[j]), std::sqrt(rule.healthy_gap_std * rule.healthy_gap_std + own)});
  }
  verdict.suspect = pickSuspect(verdict.motors, rule);
  return verdict;
}

}  // namespace propulsion_estimator
