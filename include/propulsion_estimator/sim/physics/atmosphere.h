#pragma once

namespace propulsion_estimator {
namespace sim {

/// Still air at one place and time. Density from the ideal gas law for dry air, rho = p / (R T).
struct AirConditions {
  double temperature_c = 0.0;  ///< deg C
  double pressure_pa = 0.0;  ///< Pa, static

  double densityKgM3() const;  ///< kg/m^3, p / (R T)
  /// Static pressure `height_m` above this place, in an isothermal layer (barometric formula).
  /// Against the standard atmosphere's lapse rate of 6.5 K/km the isothermal assumption errs by
  /// 0.014 Pa at 10 m, 0.12 Pa at 30 m and 1.3 Pa at 100 m: at most about one barometer sigma.
  double pressureAtHeightPa(double height_m) const;
  /// Throws FieldError (`field`.temperature_c / .pressure_pa) outside -40..60 deg C or 50..110 kPa.
  void validate(const char* field) const;
};

}  // namespace sim
}  // namespace propulsion_estimator
