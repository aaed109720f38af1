#pragma once

#include <optional>
#include <vector>

#include "propulsion_estimator/fitting/bench_dataset.h"
#include "propulsion_estimator/fitting/drive_curve_fit.h"
#include "propulsion_estimator/fitting/surface_fit.h"
#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {
namespace fitting {

/// A candidate surface with its scores; no surface when the data cannot determine it.
struct SurfaceCandidate {
  CandidateScore score;                    ///< its scores
  std::optional<ResponseSurface> surface;  ///< fitted on all rows (a drive curve: on the subsample)
  std::optional<DriveCurveFit> drive_fit;  ///< a drive curve's fit on the subsample, to refit on all rows
};

/// The band of each voltage level (VoltageBands says which), and the bands' voltages in `bands`.
std::vector<VoltageBand> voltageBandOfLevels(const BenchDataset& data, VoltageBands* bands);

/// Whether `surface` is non-decreasing in PWM and in voltage over the covered part of `domain`
/// (36 x 15 grid; a drop by more than `tolerance`, in the surface's unit, between neighbours is
/// not). Throws nothing.
bool isNonDecreasing(const ResponseSurface& surface, const ModelDomain& domain, double tolerance);
/// The number of grid cells (36 x 15 over the box, covered cells only) where `surface` falls as PWM
/// or voltage rises by more than `tolerance`, or is negative: the report's count of unphysical cells.
int unphysicalCells(const ResponseSurface& surface, const ModelDomain& domain, double tolerance);

/// Drive curves of degree 1 to DriveCurve::kMaxDegree fitted on `rows`, with the ESC's full-throttle
/// end point when the rows show one (findFullThrottle).
std::vector<SurfaceCandidate> driveCurveCandidates(const FitRows& rows);

/// The candidate chosen: among the physical ones with a held-out error, the least worst of its
/// determined scores (held-out, low-band and high-band RMSE: each candidate is judged on every
/// hold-out the data can pose to it), and within `parsimony` of that, the fewest terms. nullptr when
/// no candidate qualifies.
const SurfaceCandidate* chooseCandidate(const std::vector<SurfaceCandidate>& candidates, double parsimony);

}  // namespace fitting
}  // namespace propulsion_estimator
