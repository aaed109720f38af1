#pragma once

#include <limits>
#include <vector>

namespace propulsion_estimator {

/// Healthy flights a MotorReference needs at the least.
constexpr int kMinReferenceFlights = 3;

/// A vehicle's healthy fingerprint: each motor's mean share of the summed model thrust in steady
/// hover over flights known to be healthy, and each share's flight-to-flight spread.
struct MotorReference {
  std::vector<double> shares;      ///< per motor in rotor order, summing to 1
  std::vector<double> share_std;   ///< per motor, the standard deviation from flight to flight
  int flights = 0;                 ///< healthy flights it was learned from (at least 3)
  /// The weak-rotor gaps each healthy flight shows against the others' mean, per motor: how far a
  /// single flight's gap scatters on a healthy vehicle (its standard deviation, a share of thrust).
  std::vector<double> gap_std;
  /// What the live ESC check (onboard/model_check.h) saw of each motor on those flights: its hover
  /// rpm against the model, relative to the motors' median (0 = like the others), and its current
  /// for its speed likewise, averaged over the flights. Healthy motors differ by their parts; the
  /// check judges each motor's change from these. Empty when the flights had no ESC telemetry.
  std::vector<double> esc_rpm_deviation;
  std::vector<double> esc_current_deviation;  ///< see esc_rpm_deviation
  /// What the live ESC check saw of every motor together on those flights: the motors' median
  /// hover rpm against the model (1 = as the model says), averaged over the flights. The day's
  /// air, warm motors and the vehicle's parts move it; the check's "supply" verdict judges its
  /// change from this. NaN when unknown (then against 1).
  double esc_rpm_level = std::numeric_limits<double>::quiet_NaN();
  /// The vehicle's vertical thrust in steady flight on those flights (weighed mass times specific
  /// force) over the model's from the pulse widths: its parts, frame and propellers against the
  /// bench's. Effects are then judged as changes from it. NaN when unknown.
  double thrust_factor = std::numeric_limits<double>::quiet_NaN();
  /// Likewise over the model's thrust from the battery current less the ground draw (the diagnosis'
  /// current view; a reference learnt before 2026-12-02 has the avionics' draw in it) and from ESC
  /// telemetry's rotor speeds (its RPM view); NaN without them.
  double current_thrust_factor = std::numeric_limits<double>::quiet_NaN();
  double rpm_thrust_factor = std::numeric_limits<double>::quiet_NaN();  ///< see current_thrust_factor
  /// The air and the motors those thrust factors were flown in: the mean air density (kg/m^3) and
  /// motor temperature (deg C) over the same steady blocks. The factors hold that air and that
  /// warmth, so the diagnosis reads the day's air and the motors' warming as changes from these,
  /// not from the bench's. NaN where the flights did not give the signal.
  double air_density_kg_m3 = std::numeric_limits<double>::quiet_NaN();
  double motor_temperature_c = std::numeric_limits<double>::quiet_NaN();  ///< see air_density_kg_m3

  /// FieldError naming the field under motor_reference: shares that do not sum to 1 or are not positive,
  /// lists of different lengths (the ESC deviations: none or one per motor, both or neither), a
  /// negative spread, an ESC deviation beyond +-50 %, a thrust factor outside 0.5..1.5, an air
  /// density outside 0.3..2 kg/m^3, a motor temperature outside -60..200 deg C, fewer than 3 flights.
  void validate() const;
};

}  // namespace propulsion_estimator
