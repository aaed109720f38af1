#pragma once

namespace propulsion_estimator {

/// The packs the package takes, in cells in series: 1S to 14S (58.8 V full, the largest pack
/// multicopter ESCs are made for). Every configuration, file and command line that names a pack's
/// cells is checked against this one range.
///@{
inline constexpr int kMinCellsInSeries = 1;
inline constexpr int kMaxCellsInSeries = 14;
///@}

}  // namespace propulsion_estimator
