#pragma once

#include <optional>
#include <set>
#include <string>

#include "propulsion_estimator/fitting/bench_dataset.h"
#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {
namespace fitting {

/// How rows are grouped for cross-validation: whole groups are held out, never random rows
/// (neighbouring rows of one sweep are not independent, and a random split would reward
/// over-fitting them).
enum class FitGrouping {
  kAuto,          ///< voltage levels when there are 3 or more, else PWM levels
  kVoltageLevel,  ///< hold out one voltage level: tests interpolation across voltage
  kPwmLevel,      ///< hold out one PWM level at every voltage: the only choice with 2 voltage levels
  kLog,           ///< hold out one log file
};

/// Options of fit_surfaces: cross-validation grouping, maximum degrees, outputs left out, the
/// outside-domain policy and the metadata that override the logs'.
struct FitOptions {
  FitGrouping grouping = FitGrouping::kAuto;  ///< how rows are grouped for cross-validation
  int max_pwm_degree = 5;      ///< 1..5
  int max_voltage_degree = 3;  ///< 0..3
  /// A candidate within this share of the best held-out RMSE that has fewer terms is preferred.
  double parsimony = 0.02;
  int min_points = 10;              ///< per fitted output
  bool efficiency_surface = false;  ///< fit efficiency samples instead of deriving thrust / power
  std::set<Output> without;         ///< current, power or rpm left out of the model
  OutsideDomain outside = OutsideDomain::kClamp;  ///< what the model does outside its domain
  LevelOptions levels;  ///< how rows are sorted into voltage and PWM levels
  /// Model metadata; each overrides the logs' "# key: value" lines (esc, motor, propeller,
  /// air_temperature_c, air_pressure_pa, supply) and their ambient_temp_c / pressure_pa columns.
  /// A name neither gives is recorded as "unknown" with a note; the bench air and the supply are
  /// physics and required.
  ///@{
  std::optional<std::string> esc, motor, propeller;
  std::optional<double> air_temperature_c, air_pressure_pa;
  std::optional<SupplyKind> supply;
  ///@}

  /// Throws ConfigError naming the bad option.
  void validate() const;
};

}  // namespace fitting
}  // namespace propulsion_estimator
