#pragma once

namespace propulsion_estimator {

// Still air at one place and time. Density from the ideal gas law for dry air, rho = p / (R T).
struct AirConditions {
  double temperature_c = 0.0;
  double pressure_pa = 0.0;

  double densityKgM3() const;
  // Static pressure `height_m` above this place, in an isothermal layer (barometric formula);
  // within the few tens of metres of a hover the isothermal assumption errs by < 0.01 Pa.
  double pressureAtHeightPa(double height_m) const;
  // Throws FieldError (`field`.temperature_c / .pressure_pa) outside -40..60 deg C or 50..110 kPa.
  void validate(const char* field) const;
};

}  // namespace propulsion_estimator
