#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/gap/residual_breakdown.h"
#include "propulsion_estimator/gap/thrust_views.h"
#include "propulsion_estimator/logs/bench_log.h"

namespace propulsion_estimator {
namespace gap {

/// A bench log measured under other conditions than the model's: the load cell is the truth.
struct BenchGap {
  std::string source;                 ///< the bench log's file
  ResidualStats stats;                 ///< model thrust minus the load cell, rows with thrust above 5 % of the log's maximum
  std::vector<Breakdown> where;        ///< by voltage, and by motor temperature where logged
};

/// The load cell of `log` against the model (through a one-motor `views`) at each row's pulse
/// width and voltage, over rows with thrust above 5 % of the log's maximum, broken down by voltage
/// and motor temperature.
BenchGap benchGap(const ThrustViews& views, const BenchLog& log);

}  // namespace gap
}  // namespace propulsion_estimator
