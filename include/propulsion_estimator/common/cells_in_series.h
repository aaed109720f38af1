#pragma once

#include <string>

namespace propulsion_estimator {

/// The packs the package takes, in cells in series: 1S to 14S (58.8 V full, the largest pack
/// multicopter ESCs are made for). Every configuration, file and command line that names a pack's
/// cells is checked against this one range.
///@{
inline constexpr int kMinCellsInSeries = 1;
inline constexpr int kMaxCellsInSeries = 14;
///@}

/// "15 is outside 1..14" for a count of cells outside the range, "" within it: the problem a
/// reader that names its own field (a file's line, an option) says. Throws nothing.
inline std::string cellsInSeriesProblem(int cells) {
  if (cells >= kMinCellsInSeries && cells <= kMaxCellsInSeries) return "";
  return std::to_string(cells) + " is outside " + std::to_string(kMinCellsInSeries) + ".." +
         std::to_string(kMaxCellsInSeries);
}

}  // namespace propulsion_estimator
