#include "propulsion_estimator/sim/physics/lipo_battery.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/cells_in_series.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace sim {

void LipoBatteryParams::validate() const {
  requireWithin("battery.cells", cells, kMinCellsInSeries, kMaxCellsInSeries);
  requirePositive("battery.capacity_ah", capacity_ah, 1000.0, " Ah");
  if (ocv_soc.size() < 2 || ocv_soc.size() != ocv_cell_v.size()) {
    throw FieldError("battery.open_circuit_voltage", "soc and cell_v need the same number of points, at least 2 (got " +
                                                         std::to_string(ocv_soc.size()) + " and " +
                                                         std::to_string(ocv_cell_v.size()) + ")");
  }
  if (ocv_soc.front() != 0.0 || ocv_soc.back() != 1.0) {
    throw FieldError("battery.open_circuit_voltage.soc", "must run from 0 to 1");
  }
  for (std::size_t i = 0; i < ocv_soc.size(); ++i) {
    if (i > 0 && !(ocv_soc[i] > ocv_soc[i - 1])) {
      throw FieldError("battery.open_circuit_voltage.soc",
                       "must increase (" + formatNumber(ocv_soc[i]) + " after " + formatNumber(ocv_soc[i - 1]) + ")");
    }
    if (i > 0 && !(ocv_cell_v[i] > ocv_cell_v[i - 1])) {
      throw FieldError("battery.open_circuit_voltage.cell_v", "must increase with soc (" + formatNumber(ocv_cell_v[i]) +
                                                                  " after " + formatNumber(ocv_cell_v[i - 1]) + ")");
    }
    requireWithin("battery.open_circuit_voltage.cell_v", ocv_cell_v[i], 2.5, 4.4, " V");
  }
  requirePositive("battery.series_resistance_ohm", series_resistance_ohm, 1.0, " ohm");
  requirePositive("battery.rc_resistance_ohm", rc_resistance_ohm, 1.0, " ohm");
  requirePositive("battery.rc_capacitance_f", rc_capacitance_f, 1e7, " F");
  if (rc2_resistance_ohm != 0.0 || rc2_capacitance_f != 0.0) {
    requirePositive("battery.rc2_resistance_ohm", rc2_resistance_ohm, 1.0, " ohm");
    requirePositive("battery.rc2_capacitance_f", rc2_capacitance_f, 1e8, " F");
  }
}

double LipoBatteryParams::openCircuitVoltage(double state_of_charge) const {
  const double soc = std::clamp(state_of_charge, 0.0, 1.0);
  const auto upper = std::upper_bound(ocv_soc.begin() + 1, ocv_soc.end() - 1, soc);
  const std::size_t i = static_cast<std::size_t>(upper - ocv_soc.begin());
  const double t = (soc - ocv_soc[i - 1]) / (ocv_soc[i] - ocv_soc[i - 1]);
  return cells * (ocv_cell_v[i - 1] + t * (ocv_cell_v[i] - ocv_cell_v[i - 1]));
}

LipoBattery::LipoBattery(LipoBatteryParams params, double initial_soc) : params_(std::move(params)), soc_(initial_soc) {
  params_.validate();
  requireWithin("initial_soc", initial_soc, 0.0, 1.0);
}

double LipoBattery::sourceVoltage() const { return params_.openCircuitVoltage(soc_) - polarisationVoltage(); }

void LipoBattery::draw(double current_a, double dt_s) {
  soc_ -= current_a * dt_s / (params_.capacity_ah * 3600.0);
  const double settled = current_a * params_.rc_resistance_ohm;
  polarisation_v_ =
      settled + (polarisation_v_ - settled) * std::exp(-dt_s / (params_.rc_resistance_ohm * params_.rc_capacitance_f));
  if (params_.rc2_resistance_ohm > 0.0) {
    const double settled2 = current_a * params_.rc2_resistance_ohm;
    polarisation2_v_ = settled2 + (polarisation2_v_ - settled2) *
                                      std::exp(-dt_s / (params_.rc2_resistance_ohm * params_.rc2_capacitance_f));
  }
}

}  // namespace sim
}  // namespace propulsion_estimator
