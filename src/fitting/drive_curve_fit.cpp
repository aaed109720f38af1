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
constexpr int kCoarseSteps = 25;
constexpr int kFineSteps = 9;
constexpr int kMaxTerms = DriveCurve::kMaxDegree + 1;
// The full-throttle end point is looked for between these shares of the PWM span below its top.
constexpr double kFullThrottleNearest = 0.125;
constexpr double kFullThrottleFarthest = 0.5;
constexpr int kFullThrottleCoarseSteps = 7;
constexpr int kFullThrottleFineSteps = 9;
// An end point is taken only when it cuts the cubic drive curve's squared error by a third or more
// and its F statistic (one parameter added) passes a threshold far beyond chance for the 16 end
// points tried (F(1, inf) exceeds 20 with probability 8e-6).
constexpr double kFullThrottleErrorRatio = 1.5;
constexpr double kFullThrottleF = 20.0;
// A plateau is a gross feature: a smaller subsample finds it (and keeps a million-row fit under 1 s).
constexpr std::size_t kFullThrottleSearchRows = 4000;

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

// Moments of the full basis t^0..t^3 per (group, band) cell of some rows at one x0; any degree's
// moments are their leading block.
class CellMoments {
 public:
  CellMoments(const FitRows& rows, const std::vector<std::size_t>& picked, double x0, double x1, double scale)
      : groups_(rows.groups), cells_(rows.groups * kVoltageBandCount) {
    const double factor = 1e-3 / scale;
    for (std::size_t r : picked) {
      const double t = std::clamp(rows.pwm_us[r] - x0, 0.0, x1 - x0) * factor * rows.voltage_v[r];
      const double y = rows.y[r];
      const double t2 = t * t, t3 = t2 * t;
      Raw& cell = cells_[rows.group[r] * kVoltageBandCount + static_cast<int>(rows.band[r])];
      cell.power[1] += t;
      cell.power[2] += t2;
      cell.power[3] += t3;
      cell.power[4] += t2 * t2;
      cell.power[5] += t3 * t2;
      cell.power[6] += t3 * t3;
      cell.ty[0] += y;
      cell.ty[1] += t * y;
      cell.ty[2] += t2 * y;
      cell.ty[3] += t3 * y;
      cell.yty += y * y;
      ++cell.n;
    }
  }
  Moments total(int terms) const { return sum(terms, [](int, int) { return true; }); }
  Moments group(int terms, int g) const { return sum(terms, [&](int cg, int) { return cg == g; }); }
  Moments band(int terms, VoltageBand b) const {
    return sum(terms, [&](int, int cb) { return cb == static_cast<int>(b); });
  }

 private:
  // Sums of t^k (k = 0..6) and t^k y (k = 0..3): X'X of the basis t^i is the Hankel matrix of them.
  struct Raw {
    double power[2 * kMaxTerms - 1] = {};
    double ty[kMaxTerms] = {};
    double yty = 0.0;
    long n = 0;
  };
  template <typename Pick>
  Moments sum(int terms, Pick pick) const {
    Raw raw;
    for (int g = 0; g < groups_; ++g) {
      for (int b = 0; b < kVoltageBandCount; ++b) {
        if (!pick(g, b)) continue;
        const Raw& cell = cells_[g * kVoltageBandCount + b];
        for (int k = 1; k < 2 * kMaxTerms - 1; ++k) raw.power[k] += cell.power[k];
        for (int k = 0; k < kMaxTerms; ++k) raw.ty[k] += cell.ty[k];
        raw.yty += cell.yty;
        raw.n += cell.n;
      }
    }
    Moments m(terms);
    raw.power[0] = static_cast<double>(raw.n);
    for (int i = 0; i < terms; ++i) {
      m.xty(i) = raw.ty[i];
      for (int j = 0; j < terms; ++j) m.xtx(i, j) = raw.power[i + j];
    }
    m.yty = raw.yty;
    m.n = raw.n;
    return m;
  }
  int groups_;
  std::vector<Raw> cells_;
};

// One (x0, x1) of the grid: its scale and moments.
struct Trial {
  double x0;
  double x1;
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
        Moments m = t.cells.total(terms);
        m -= held(t);
        return m;
      },
      terms);
  if (!trial) return kNaN;
  const Moments out = held(*trial);
  return out.n > 0 ? std::sqrt(out.sse(beta) / static_cast<double>(out.n)) : kNaN;
}

// The curve of coefficients fitted on t = u / scale.
DriveCurve toCurve(double x0, double x1, double scale, const Vector& beta) {
  std::vector<double> coefficients(beta.size());
  for (int k = 0; k < beta.size(); ++k) coefficients[k] = beta(k) / std::pow(scale, k);
  return DriveCurve(x0, std::move(coefficients), x1);
}

// A grid of x0 from `from` to `to` for each end point in `ends` (below x0: none taken).
std::vector<Trial> trialsOnGrid(const FitRows& rows, const std::vector<std::size_t>& picked, double from, double to,
                                int steps, const std::vector<double>& ends, double v_max, double pwm_max) {
  std::vector<Trial> trials;
  for (double x1 : ends) {
    for (int s = 0; s < steps; ++s) {
      const double x0 = from + (to - from) * s / (steps - 1);
      if (!(x1 > x0)) continue;
      const double scale = std::max(1e-9, (std::min(pwm_max, x1) - x0) * 1e-3 * v_max);
      trials.push_back({x0, x1, scale, CellMoments(rows, picked, x0, x1, scale)});
    }
  }
  return trials;
}

// Full-throttle end points worth trying: from an eighth to half of the PWM span below its top, each
// with rows at two PWM values or more above it (a plateau the bench logged, not one point).
std::vector<double> fullThrottleGrid(const FitRows& rows, const std::vector<std::size_t>& picked, double pwm_lo,
                                     double pwm_hi, int steps) {
  const double span = pwm_hi - pwm_lo;
  std::vector<double> ends;
  for (int s = 0; s < steps; ++s) {
    const double x1 = pwm_hi - span * (kFullThrottleNearest + (kFullThrottleFarthest - kFullThrottleNearest) * s /
                                                                   (steps - 1));
    double first_above = kNaN;
    bool two_above = false;
    for (std::size_t r : picked) {
      const double x = rows.pwm_us[r];
      if (!(x > x1)) continue;
      if (std::isnan(first_above)) {
        first_above = x;
      } else if (x != first_above) {
        two_above = true;
        break;
      }
    }
    if (two_above) ends.push_back(x1);
  }
  return ends;
}

// Held-out RMSE pooled over the groups, as GroupedLeastSquares::heldOutRmse pools them.
double pooledHeldOutRmse(const std::vector<Trial>& trials, int groups, int terms) {
  double sse = 0.0;
  long n = 0;
  for (int g = 0; g < groups; ++g) {
    const long held = trials.front().cells.group(terms, g).n;
    if (held == 0) continue;
    const double rmse = heldOutRmse(trials, [g, terms](const Trial& t) { return t.cells.group(terms, g); }, terms);
    if (std::isnan(rmse)) return kNaN;
    sse += rmse * rmse * static_cast<double>(held);
    n += held;
  }
  return n > 0 ? std::sqrt(sse / static_cast<double>(n)) : kNaN;
}

// An even subsample of at most `max_rows` rows, and the PWM and voltage range of all rows.
struct Subsample {
  std::vector<std::size_t> picked;
  double pwm_lo = 0.0, pwm_hi = 0.0, v_max = 0.0;

  Subsample(const FitRows& rows, std::size_t max_rows) {
    const std::size_t stride = std::max<std::size_t>(1, rows.size() / max_rows);
    for (std::size_t r = 0; r < rows.size(); r += stride) picked.push_back(r);
    const auto [lo, hi] = std::minmax_element(rows.pwm_us.begin(), rows.pwm_us.end());
    pwm_lo = *lo;
    pwm_hi = *hi;
    v_max = *std::max_element(rows.voltage_v.begin(), rows.voltage_v.end());
  }
  double span() const { return pwm_hi - pwm_lo; }
  double step() const { return span() / (kCoarseSteps - 1); }
  // x0 from half a span below the bench's lowest PWM to its middle, for each end point in `ends`.
  std::vector<Trial> coarse(const FitRows& rows, const std::vector<double>& ends) const {
    return trialsOnGrid(rows, picked, pwm_lo - 0.5 * span(), pwm_lo + 0.5 * span(), kCoarseSteps, ends, v_max, pwm_hi);
  }
  // x0 within a coarse step of `x0`, finer, for each end point in `ends`.
  std::vector<Trial> around(const FitRows& rows, double x0, const std::vector<double>& ends) const {
    return trialsOnGrid(rows, picked, x0 - step(), x0 + step(), kFineSteps, ends, v_max, pwm_hi);
  }
};



// One degree's fit: x0 refined around the coarse grid's best (x1 as in `coarse`), scores, and the
// final coefficients on the subsample.
std::optional<DriveCurveFit> fitDegree(const FitRows& rows, const Subsample& sample, const std::vector<Trial>& coarse,
                                       int degree) {
  const int terms = degree + 1;
  const auto [coarse_best, unused] = bestTrial(coarse, [terms](const Trial& t) { return t.cells.total(terms); }, terms);
  if (!coarse_best) return std::nullopt;
  const std::vector<Trial> trials = sample.around(rows, coarse_best->x0, {coarse_best->x1});
  DriveCurveFit fit;
  fit.held_out_rmse = pooledHeldOutRmse(trials, rows.groups, terms);
  fit.low_band_rmse =
      heldOutRmse(trials, [terms](const Trial& t) { return t.cells.band(terms, VoltageBand::kLow); }, terms);
  fit.high_band_rmse =
      heldOutRmse(trials, [terms](const Trial& t) { return t.cells.band(terms, VoltageBand::kHigh); }, terms);
  // The final curve: x0 chosen on all (sampled) rows, coefficients on all rows.
  const auto [chosen, sampled_beta] =
      bestTrial(trials, [terms](const Trial& t) { return t.cells.total(terms); }, terms);
  if (!chosen) return std::nullopt;
  fit.curve = toCurve(chosen->x0, chosen->x1, chosen->scale, sampled_beta);
  fit.scale = chosen->scale;
  return fit;
}

// The least squared error of a cubic drive curve over `trials`, and the trial that reaches it.
std::pair<const Trial*, double> leastCubicError(const std::vector<Trial>& trials) {
  const auto [trial, beta] = bestTrial(trials, [](const Trial& t) { return t.cells.total(kMaxTerms); }, kMaxTerms);
  if (!trial) return {nullptr, kNaN};
  return {trial, trial->cells.total(kMaxTerms).sse(beta)};
}

}  // namespace

double findFullThrottle(const FitRows& rows) {
  if (rows.size() < static_cast<std::size_t>(kMaxTerms + 3)) return DriveCurve::kNoFullThrottle;
  const Subsample sample(rows, kFullThrottleSearchRows);
  const std::vector<double> ends = fullThrottleGrid(rows, sample.picked, sample.pwm_lo, sample.pwm_hi,
                                                    kFullThrottleCoarseSteps);
  if (ends.empty()) return DriveCurve::kNoFullThrottle;
  // The cubic without an end point, x0 refined as fitDegree refines it: the fairest rival.
  const std::vector<Trial> open_coarse = sample.coarse(rows, {DriveCurve::kNoFullThrottle});
  const Trial* open_best = leastCubicError(open_coarse).first;
  if (!open_best) return DriveCurve::kNoFullThrottle;
  const double open_sse = leastCubicError(sample.around(rows, open_best->x0, {DriveCurve::kNoFullThrottle})).second;
  const std::vector<Trial> ended_coarse = sample.coarse(rows, ends);
  const Trial* ended_best = leastCubicError(ended_coarse).first;
  if (!ended_best) return DriveCurve::kNoFullThrottle;
  const double end_step = sample.span() * (kFullThrottleFarthest - kFullThrottleNearest) / (kFullThrottleCoarseSteps - 1);
  std::vector<double> fine_ends;
  for (int s = 0; s < kFullThrottleFineSteps; ++s) {
    const double x1 = ended_best->x1 + end_step * (2.0 * s / (kFullThrottleFineSteps - 1) - 1.0);
    if (x1 <= ends.front()) fine_ends.push_back(x1);
  }
  const std::vector<Trial> ended_fine = sample.around(rows, ended_best->x0, fine_ends);
  const auto [ended, ended_sse] = leastCubicError(ended_fine);
  if (!ended || !(open_sse >= kFullThrottleErrorRatio * ended_sse)) return DriveCurve::kNoFullThrottle;
  // F statistic of the one parameter x1 added, against a threshold far beyond chance for the grid's tries.
  const double residual_dof = static_cast<double>(sample.picked.size()) - (kMaxTerms + 2);
  if (residual_dof < 1.0 || !((open_sse - ended_sse) * residual_dof >= kFullThrottleF * ended_sse)) {
    return DriveCurve::kNoFullThrottle;
  }
  return ended->x1;
}

std::vector<std::optional<DriveCurveFit>> fitDriveCurves(const FitRows& rows, double pwm_full_us) {
  std::vector<std::optional<DriveCurveFit>> fits(DriveCurve::kMaxDegree);
  if (rows.size() < 4) return fits;
  const Subsample sample(rows, kSearchRows);
  const std::vector<Trial> coarse = sample.coarse(rows, {pwm_full_us});
  const int fewest_rows = std::isfinite(pwm_full_us) ? 4 : 3;  // coefficients + 2, x1 counted
  for (int degree = 1; degree <= DriveCurve::kMaxDegree; ++degree) {
    if (rows.size() < static_cast<std::size_t>(degree + fewest_rows)) continue;
    fits[degree - 1] = fitDegree(rows, sample, coarse, degree);
  }
  return fits;
}

DriveCurve refitOnAllRows(const FitRows& rows, const DriveCurveFit& fit) {
  std::vector<std::size_t> all(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) all[r] = r;
  const double x0 = fit.curve.pwmZeroUs(), x1 = fit.curve.pwmFullUs();
  const std::optional<Vector> beta =
      nonNegativeSolve(CellMoments(rows, all, x0, x1, fit.scale).total(fit.curve.degree() + 1));
  return beta ? toCurve(x0, x1, fit.scale, *beta) : fit.curve;
}

}  // namespace fitting
}  // namespace propulsion_estimator
