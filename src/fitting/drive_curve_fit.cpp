#include "propulsion_estimator/fitting/drive_curve_fit.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "propulsion_estimator/common/not_a_number.h"

namespace propulsion_estimator {
namespace fitting {
namespace {

constexpr std::size_t kSearchRows = 20000;
constexpr int kCoarseSteps = 41;
constexpr int kFineSteps = 21;
constexpr int kMaxTerms = DriveCurve::kMaxDegree + 1;

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

// Sufficient statistics of the basis t^k (t = u / scale) for some rows.
struct Moments {
  Matrix xtx;
  Vector xty;
  double yty = 0.0;
  long n = 0;

  explicit Moments(int terms) : xtx(Matrix::Zero(terms, terms)), xty(Vector::Zero(terms)) {}
  Moments& operator+=(const Moments& o) {
    xtx += o.xtx;
    xty += o.xty;
    yty += o.yty;
    n += o.n;
    return *this;
  }
  Moments& operator-=(const Moments& o) {
    xtx -= o.xtx;
    xty -= o.xty;
    yty -= o.yty;
    n -= o.n;
    return *this;
  }
  double sse(const Vector& beta) const { return std::max(0.0, yty - 2.0 * beta.dot(xty) + beta.dot(xtx * beta)); }
};

// Least squares with every coefficient >= 0: the optimum is the unconstrained solution on some
// subset of free coefficients (the others zero) that is itself non-negative; with at most four
// coefficients every subset is tried.
std::optional<Vector> nonNegativeSolve(const Moments& m) {
  const int terms = static_cast<int>(m.xty.size());
  std::optional<Vector> best;
  double best_sse = std::numeric_limits<double>::infinity();
  for (int mask = 1; mask < (1 << terms); ++mask) {
    std::vector<int> free;
    for (int k = 0; k < terms; ++k) {
      if (mask & (1 << k)) free.push_back(k);
    }
    const int f = static_cast<int>(free.size());
    Matrix a(f, f);
    Vector b(f);
    for (int i = 0; i < f; ++i) {
      b(i) = m.xty(free[i]);
      for (int j = 0; j < f; ++j) a(i, j) = m.xtx(free[i], free[j]);
    }
    const Eigen::LDLT<Matrix> ldlt(a);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) continue;
    const Vector pivots = ldlt.vectorD().cwiseAbs();
    if (!(pivots.minCoeff() > 1e-12 * pivots.maxCoeff())) continue;
    const Vector solution = ldlt.solve(b);
    if ((solution.array() < 0.0).any()) continue;
    Vector beta = Vector::Zero(terms);
    for (int i = 0; i < f; ++i) beta(free[i]) = solution(i);
    const double sse = m.sse(beta);
    if (sse < best_sse) {
      best_sse = sse;
      best = beta;
    }
  }
  return best;
}

// Moments per (group, band) cell of some rows at one x0.
class CellMoments {
 public:
  CellMoments(const FitRows& rows, const std::vector<std::size_t>& picked, int terms, double x0, double scale)
      : groups_(rows.groups), cells_(rows.groups * kVoltageBandCount, Moments(terms)), total_(terms) {
    double t_pow[kMaxTerms];
    for (std::size_t r : picked) {
      const double t = std::max(0.0, rows.pwm_us[r] - x0) * 1e-3 * rows.voltage_v[r] / scale;
      t_pow[0] = 1.0;
      for (int k = 1; k < terms; ++k) t_pow[k] = t_pow[k - 1] * t;
      Moments& cell = cells_[rows.group[r] * kVoltageBandCount + static_cast<int>(rows.band[r])];
      for (int i = 0; i < terms; ++i) {
        cell.xty(i) += t_pow[i] * rows.y[r];
        for (int j = 0; j <= i; ++j) cell.xtx(i, j) += t_pow[i] * t_pow[j];
      }
      cell.yty += rows.y[r] * rows.y[r];
      ++cell.n;
    }
    for (Moments& cell : cells_) {
      cell.xtx.template triangularView<Eigen::StrictlyUpper>() = cell.xtx.transpose();
      total_ += cell;
    }
  }
  const Moments& total() const { return total_; }
  Moments group(int g) const { return sum([&](int cg, int) { return cg == g; }); }
  Moments band(VoltageBand b) const { return sum([&](int, int cb) { return cb == static_cast<int>(b); }); }
  int groups() const { return groups_; }

 private:
  template <typename Pick>
  Moments sum(Pick pick) const {
    Moments m(static_cast<int>(total_.xty.size()));
    for (int g = 0; g < groups_; ++g) {
      for (int b = 0; b < kVoltageBandCount; ++b) {
        if (pick(g, b)) m += cells_[g * kVoltageBandCount + b];
      }
    }
    return m;
  }
  int groups_;
  std::vector<Moments> cells_;
  Moments total_;
};

// One x0 of the grid: its scale and moments.
struct Trial {
  double x0;
  double scale;
  CellMoments cells;
};

// The trial whose fit on `train(trial)` has the least training error, and its coefficients.
template <typename Train>
std::pair<const Trial*, Vector> bestTrial(const std::vector<Trial>& trials, Train train, int terms) {
  const Trial* best = nullptr;
  Vector best_beta = Vector::Zero(terms);
  double best_sse = std::numeric_limits<double>::infinity();
  for (const Trial& trial : trials) {
    const Moments m = train(trial);
    if (m.n < terms + 2) continue;
    const std::optional<Vector> beta = nonNegativeSolve(m);
    if (!beta) continue;
    const double sse = m.sse(*beta);
    if (sse < best_sse) {
      best_sse = sse;
      best = &trial;
      best_beta = *beta;
    }
  }
  return {best, best_beta};
}

// RMSE of the rows held out by `held(trial)` with x0 and coefficients chosen on the rest.
template <typename Held>
double heldOutRmse(const std::vector<Trial>& trials, Held held, int terms) {
  const auto [trial, beta] = bestTrial(
      trials,
      [&](const Trial& t) {
        Moments m = t.cells.total();
        m -= held(t);
        return m;
      },
      terms);
  if (!trial) return kNaN;
  const Moments out = held(*trial);
  return out.n > 0 ? std::sqrt(out.sse(beta) / static_cast<double>(out.n)) : kNaN;
}

std::vector<Trial> trialsOnGrid(const FitRows& rows, const std::vector<std::size_t>& picked, int terms, double from,
                                double to, int steps, double v_max, double pwm_max) {
  std::vector<Trial> trials;
  for (int s = 0; s < steps; ++s) {
    const double x0 = from + (to - from) * s / (steps - 1);
    const double scale = std::max(1e-9, (pwm_max - x0) * 1e-3 * v_max);
    trials.push_back({x0, scale, CellMoments(rows, picked, terms, x0, scale)});
  }
  return trials;
}

}  // namespace

std::optional<DriveCurveFit> fitDriveCurve(const FitRows& rows, int degree) {
  const int terms = degree + 1;
  if (rows.size() < static_cast<std::size_t>(terms + 2)) return std::nullopt;
  const std::size_t stride = std::max<std::size_t>(1, rows.size() / kSearchRows);
  std::vector<std::size_t> picked;
  for (std::size_t r = 0; r < rows.size(); r += stride) picked.push_back(r);
  const auto [pwm_lo, pwm_hi] = std::minmax_element(rows.pwm_us.begin(), rows.pwm_us.end());
  const double v_max = *std::max_element(rows.voltage_v.begin(), rows.voltage_v.end());
  const double span = *pwm_hi - *pwm_lo;
  // x0 from half a span below the bench's lowest PWM to its middle; then finer around the best.
  std::vector<Trial> coarse =
      trialsOnGrid(rows, picked, terms, *pwm_lo - 0.5 * span, *pwm_lo + 0.5 * span, kCoarseSteps, v_max, *pwm_hi);
  const auto [coarse_best, unused] = bestTrial(coarse, [](const Trial& t) { return t.cells.total(); }, terms);
  if (!coarse_best) return std::nullopt;
  const double step = span / (kCoarseSteps - 1);
  const std::vector<Trial> trials = trialsOnGrid(rows, picked, terms, coarse_best->x0 - step, coarse_best->x0 + step,
                                                 kFineSteps, v_max, *pwm_hi);

  DriveCurveFit fit;
  // Pooled over the groups, as GroupedLeastSquares::heldOutRmse pools them.
  double sse = 0.0;
  long n = 0;
  for (int g = 0; g < rows.groups; ++g) {
    const double rmse = heldOutRmse(trials, [g](const Trial& t) { return t.cells.group(g); }, terms);
    const long held = trials.front().cells.group(g).n;
    if (held == 0) continue;
    if (std::isnan(rmse)) {
      sse = kNaN;
      break;
    }
    sse += rmse * rmse * static_cast<double>(held);
    n += held;
  }
  fit.held_out_rmse = n > 0 ? std::sqrt(sse / static_cast<double>(n)) : kNaN;
  fit.low_band_rmse = heldOutRmse(trials, [](const Trial& t) { return t.cells.band(VoltageBand::kLow); }, terms);
  fit.high_band_rmse = heldOutRmse(trials, [](const Trial& t) { return t.cells.band(VoltageBand::kHigh); }, terms);

  // The final curve: x0 chosen on all (sampled) rows, coefficients on all rows.
  const auto [chosen, sampled_beta] = bestTrial(trials, [](const Trial& t) { return t.cells.total(); }, terms);
  if (!chosen) return std::nullopt;
  std::vector<std::size_t> all(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) all[r] = r;
  const CellMoments full(rows, stride == 1 ? picked : all, terms, chosen->x0, chosen->scale);
  const std::optional<Vector> beta = stride == 1 ? std::optional<Vector>(sampled_beta) : nonNegativeSolve(full.total());
  if (!beta) return std::nullopt;
  std::vector<double> coefficients(terms);
  for (int k = 0; k < terms; ++k) coefficients[k] = (*beta)(k) / std::pow(chosen->scale, k);
  fit.curve = DriveCurve(chosen->x0, std::move(coefficients));
  return fit;
}

}  // namespace fitting
}  // namespace propulsion_estimator
