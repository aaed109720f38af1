#include "propulsion_estimator/model/motor_reference.h"

#include <cmath>
#include <string>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
void MotorReference::validate() const {
  if (flights < kMinReferenceFlights) {
    throw FieldError("motor_reference.flights",
                     std::to_string(flights) + " is fewer than the " + std::to_string(kMinReferenceFlights) + " needed");
  }
  if (share_std.size() != shares.size() || gap_std.size() != shares.size()) {
    throw FieldError("motor_reference.share_std", std::to_string(share_std.size()) + " and gap_std " +
                                                      std::to_string(gap_std.size()) + " values for " +
                                                      std::to_string(shares.size()) + " shares");
  }
  double sum = 0.0;
  for (std::size_t k = 0; k < shares.size(); ++k) {
    requireWithin("motor_reference.shares[" + std::to_string(k) + "]", shares[k], 1e-6, 1.0);
    requireWithin("motor_reference.share_std[" + std::to_string(k) + "]", share_std[k], 0.0, 1.0);
    requireWithin("motor_reference.gap_std[" + std::to_string(k) + "]", gap_std[k], 0.0, 1.0);
    sum += shares[k];
  }
  if (esc_rpm_deviation.size() != esc_current_deviation.size() ||
      (!esc_rpm_deviation.empty() && esc_rpm_deviation.size() != shares.size())) {
    throw FieldError("motor_reference.esc_rpm_deviation",
                     std::to_string(esc_rpm_deviation.size()) + " and esc_current_deviation " +
                         std::to_string(esc_current_deviation.size()) + " values for " + std::to_string(shares.size()) +
                         " shares (none or one per motor, both)");
  }
  if (!std::isnan(esc_rpm_level)) requireWithin("motor_reference.esc_rpm_level", esc_rpm_level, 0.5, 1.5);
  for (std::size_t k = 0; k < esc_rpm_deviation.size(); ++k) {
    requireWithin("motor_reference.esc_rpm_deviation[" + std::to_string(k) + "]", esc_rpm_deviation[k], -0.5, 0.5);
    requireWithin("motor_reference.esc_current_deviation[" + std::to_string(k) + "]", esc_current_deviation[k], -0.5,
                  0.5);
  }
  for (const auto& [key, value] : {std::make_pair("thrust_factor", thrust_factor),
                                   std::make_pair("current_thrust_factor", current_thrust_factor),
                                   std::make_pair("rpm_thrust_factor", rpm_thrust_factor)}) {
    if (!std::isnan(value)) requireWithin(std::string("motor_reference.") + key, value, 0.5, 1.5);
  }
  if (!std::isnan(air_density_kg_m3)) {
    requireWithin("motor_reference.air_density_kg_m3", air_density_kg_m3, 0.3, 2.0, " kg/m^3");
  }
  if (!std::isnan(motor_temperature_c)) {
    requireWithin("motor_reference.motor_temperature_c", motor_temperature_c, -60.0, 200.0, " deg C");
  }
  if (std::abs(sum - 1.0) > 1e-3) {
    throw FieldError("motor_reference.shares", "they sum to " + formatPrintf("%.4f", sum) + ", not 1");
  }
}

}  // namespace propulsion_estimator
