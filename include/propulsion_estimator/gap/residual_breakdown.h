#pragma once

#include <functional>
#include <string>
#include <vector>

#include "propulsion_estimator/gap/blocks.h"

namespace propulsion_estimator {
namespace gap {

/// Bias and spread of residuals (model minus truth) in N and in percent of the truth.
struct ResidualStats {
  int samples = 0;         ///< blocks behind the figures
  double bias_n = 0.0;     ///< mean residual, N
  double rmse_n = 0.0;     ///< root mean square residual, N
  double bias_pct = 0.0;   ///< mean residual, % of the truth
  double rmse_pct = 0.0;   ///< root mean square residual, % of the truth
};

/// One bin of a breakdown of the residual.
struct Bin {
  std::string label;    ///< the bin's range or name
  ResidualStats stats;  ///< the residual within it
};

/// The residual broken down by one quantity, or why it could not be.
struct Breakdown {
  std::string name;  ///< "height_above_ground_m", "phase", ...
  std::vector<Bin> bins;  ///< in the quantity's order
  std::string unavailable;  ///< empty, or "needs /mavros/rangefinder/rangefinder"
};

/// A view of a block's vertical thrust, N (NaN where it has none).
using BlockView = std::function<double(const Block&)>;

/// The residual statistics of `view` against each block's truth, over the blocks where the view is finite.
ResidualStats statsOf(const std::vector<const Block*>& blocks, const BlockView& view);

/// The payload error the node would make with thrusts `view_n` (one per block, N), tare on the
/// lightest weighed segment: RMS over the heavier segments (payload above 20 g) of (estimated -
/// weighed) / weighed payload, %; NaN with fewer than two segments.
double payloadErrorPct(const std::vector<Block>& blocks, const std::vector<double>& view_n);

/// The residual of `view` broken down by `value` over fixed `edges`, bins labelled with `format`;
/// "needs <needs>" when no block has the value.
Breakdown breakdownBy(const std::string& name, const std::vector<const Block*>& blocks, const BlockView& value,
                      const std::vector<double>& edges, const BlockView& view, const char* format,
                      const std::string& needs);

/// Edges at the quantiles of `value` for `bins` bins, for quantities without natural bins.
std::vector<double> quantileEdges(const std::vector<const Block*>& blocks, const BlockView& value, int bins);

}  // namespace gap
}  // namespace propulsion_estimator
