#include "propulsion_estimator/onboard/ocv_curve.h"

#include <algorithm>
#include <utility>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {

OcvCurve OcvCurve::lipo() {
  return OcvCurve({0.0, 0.05, 0.10, 0.15, 0.20, 0.25, 0.30, 0.35, 0.40, 0.45, 0.50, 0.55, 0.60, 0.65, 0.70, 0.75, 0.80,
                   0.85, 0.90, 0.95, 1.0},
                  {3.27, 3.61, 3.69, 3.71, 3.73, 3.75, 3.77, 3.79, 3.80, 3.82, 3.84, 3.85, 3.87, 3.91, 3.95, 3.98, 4.02,
                   4.08, 4.11, 4.15, 4.20},
                  "lipo");
}

OcvCurve OcvCurve::liIon() {
  return OcvCurve({0.0, 0.05, 0.10, 0.20, 0.30, 0.40, 0.50, 0.60, 0.70, 0.80, 0.90, 1.0},
                  {3.00, 3.30, 3.45, 3.55, 3.62, 3.68, 3.73, 3.80, 3.88, 3.97, 4.07, 4.19}, "li_ion");
}

OcvCurve OcvCurve::named(const std::string& chemistry, const std::string& field) {
  if (chemistry == "lipo") return lipo();
  if (chemistry == "li_ion") return liIon();
  throw FieldError(field, "\"" + chemistry + "\" is not lipo or li_ion");
}

OcvCurve::OcvCurve(std::vector<double> soc, std::vector<double> cell_v, const std::string& field)
    : soc_(std::move(soc)), cell_v_(std::move(cell_v)) {
  if (soc_.size() < 2 || soc_.size() != cell_v_.size()) {
    throw FieldError(field, "soc and cell_v need the same number of points, at least 2 (got " +
                                std::to_string(soc_.size()) + " and " + std::to_string(cell_v_.size()) + ")");
  }
  if (soc_.front() != 0.0 || soc_.back() != 1.0) throw FieldError(field + "/soc", "must run from 0 to 1");
  for (std::size_t i = 0; i < soc_.size(); ++i) {
    requireWithin(field + "/cell_v", cell_v_[i], 2.0, 4.5, " V");
    if (i == 0) continue;
    if (!(soc_[i] > soc_[i - 1])) {
      throw FieldError(field + "/soc", "must increase (" + formatNumber(soc_[i]) + " after " + formatNumber(soc_[i - 1]) + ")");
    }
    if (!(cell_v_[i] > cell_v_[i - 1])) {
      throw FieldError(field + "/cell_v",
                       "must increase with soc (" + formatNumber(cell_v_[i]) + " after " + formatNumber(cell_v_[i - 1]) + ")");
    }
  }
}

std::size_t OcvCurve::segment(double state_of_charge) const {
  const auto upper = std::upper_bound(soc_.begin() + 1, soc_.end() - 1, state_of_charge);
  return static_cast<std::size_t>(upper - soc_.begin());
}

double OcvCurve::cellVoltage(double state_of_charge) const {
  const double s = std::clamp(state_of_charge, 0.0, 1.0);
  const std::size_t i = segment(s);
  return cell_v_[i - 1] + (s - soc_[i - 1]) * slope(s);
}

double OcvCurve::slope(double state_of_charge) const {
  const std::size_t i = segment(std::clamp(state_of_charge, 0.0, 1.0));
  return (cell_v_[i] - cell_v_[i - 1]) / (soc_[i] - soc_[i - 1]);
}

double OcvCurve::stateOfCharge(double cell_v) const {
  if (cell_v <= cell_v_.front()) return 0.0;
  if (cell_v >= cell_v_.back()) return 1.0;
  const auto upper = std::upper_bound(cell_v_.begin() + 1, cell_v_.end() - 1, cell_v);
  const std::size_t i = static_cast<std::size_t>(upper - cell_v_.begin());
  return soc_[i - 1] + (cell_v - cell_v_[i - 1]) / (cell_v_[i] - cell_v_[i - 1]) * (soc_[i] - soc_[i - 1]);
}

}  // namespace propulsion_estimator
