#include "propulsion_estimator/gap/residual_breakdown.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace gap {

ResidualStats statsOf(const std::vector<const Block*>& blocks, const BlockView& view) {
  ResidualStats stats;
  double sum_rel = 0.0, sum_rel2 = 0.0, sum_n = 0.0, sum_n2 = 0.0;
  for (const Block* block : blocks) {
    const double v = view(*block);
    if (!std::isfinite(v)) continue;
    const double diff = v - block->truth_n;
    const double rel = diff / block->truth_n;
    sum_rel += rel;
    sum_rel2 += rel * rel;
    sum_n += diff;
    sum_n2 += diff * diff;
    ++stats.samples;
  }
  if (stats.samples == 0) return stats;
  stats.bias_pct = 100.0 * sum_rel / stats.samples;
  stats.rmse_pct = 100.0 * std::sqrt(sum_rel2 / stats.samples);
  stats.bias_n = sum_n / stats.samples;
  stats.rmse_n = std::sqrt(sum_n2 / stats.samples);
  return stats;
}

// The payload error the node would make, tare on the lightest segment: RMS over the heavier
// segments of (estimated payload - weighed payload) / weighed payload, %.
double payloadErrorPct(const std::vector<Block>& blocks, const std::vector<double>& view_n) {
  std::map<std::pair<int, int>, std::pair<double, int>> estimate;
  std::map<std::pair<int, int>, double> weighed;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!std::isfinite(view_n[i])) continue;
    const auto key = std::make_pair(blocks[i].flight, blocks[i].segment);
    estimate[key].first += view_n[i] / blocks[i].specific_force_up_m_s2;
    estimate[key].second += 1;
    weighed[key] = blocks[i].mass_kg;
  }
  if (estimate.size() < 2) return kNaN;
  auto lightest = weighed.begin();
  for (auto it = weighed.begin(); it != weighed.end(); ++it) {
    if (it->second < lightest->second) lightest = it;
  }
  const double tare = estimate[lightest->first].first / estimate[lightest->first].second;
  double sum = 0.0;
  int count = 0;
  for (const auto& [key, mass] : weighed) {
    const double payload = mass - lightest->second;
    if (payload < 0.02) continue;
    const double estimated = estimate[key].first / estimate[key].second - tare;
    const double error = (estimated - payload) / payload;
    sum += error * error;
    ++count;
  }
  return count > 0 ? 100.0 * std::sqrt(sum / count) : kNaN;
}

// The breakdown of the PWM view's residual by a quantity, over fixed edges.
Breakdown breakdownBy(const std::string& name, const std::vector<const Block*>& blocks,
                      const BlockView& value, const std::vector<double>& edges,
                      const BlockView& view, const char* format, const std::string& needs) {
  Breakdown breakdown;
  breakdown.name = name;
  std::vector<std::vector<const Block*>> bins(edges.size() + 1);
  int with_value = 0;
  for (const Block* block : blocks) {
    const double v = value(*block);
    if (!std::isfinite(v)) continue;
    ++with_value;
    const std::size_t bin = std::upper_bound(edges.begin(), edges.end(), v) - edges.begin();
    bins[bin].push_back(block);
  }
  if (with_value == 0) {
    breakdown.unavailable = "needs " + needs;
    return breakdown;
  }
  for (std::size_t b = 0; b < bins.size(); ++b) {
    if (bins[b].empty()) continue;
    std::string label;
    if (b == 0) {
      label = "< " + formatPrintf(format, edges.front());
    } else if (b == edges.size()) {
      label = ">= " + formatPrintf(format, edges.back());
    } else {
      label = formatPrintf(format, edges[b - 1]) + " - " + formatPrintf(format, edges[b]);
    }
    breakdown.bins.push_back({label, statsOf(bins[b], view)});
  }
  return breakdown;
}

// Edges at quantiles of a quantity, rounded to the format, for quantities without natural bins.
std::vector<double> quantileEdges(const std::vector<const Block*>& blocks, const BlockView& value,
                                  int bins) {
  std::vector<double> values;
  for (const Block* block : blocks) {
    const double v = value(*block);
    if (std::isfinite(v)) values.push_back(v);
  }
  std::vector<double> edges;
  if (values.size() < 2) return {0.0};
  std::sort(values.begin(), values.end());
  for (int i = 1; i < bins; ++i) {
    const double edge = values[values.size() * i / bins];
    if (edges.empty() || edge > edges.back() + 1e-9) edges.push_back(edge);
  }
  if (edges.empty()) edges.push_back(values.front());
  return edges;
}

}  // namespace gap
}  // namespace propulsion_estimator
