#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/offline/flight_estimate.h"

namespace propulsion_estimator {
namespace offline {

/// The estimates table `estimate` writes (estimates.csv): one row per kept sample, SI units, the
/// columns time_s, voltage_v, thrust_n, current_a, power_w, lifted_mass_kg, hovering (0 or 1),
/// total_mass_kg, mass_std_kg, payload_kg, motors_out_of_domain, then thrust_<k>_n per rotor k = 1..n.
/// A NaN is an empty cell.
std::string estimateCsv(const std::vector<EstimateSample>& samples);

/// Reads a table estimateCsv wrote. Throws DataError naming `source`, the line and the column for a
/// missing column, a rotor column out of order, or a cell that is not a number (an empty cell is NaN).
std::vector<EstimateSample> parseEstimateCsv(const std::string& text, const std::string& source);

}  // namespace offline
}  // namespace propulsion_estimator
