#pragma once

#include <string>

#include <Eigen/Core>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/onboard/forgetting_line_fit.h"
#include "propulsion_estimator/onboard/ocv_curve.h"

namespace propulsion_estimator {

/// What the pack's state is estimated from: the user's cells and rated capacity, the cells'
/// open-circuit curve, and how far a real pack may lie off that curve.
struct BatteryEstimatorConfig {
  int cells = 0;              ///< in series
  double capacity_ah = 0.0;   ///< Ah; the rated capacity
  OcvCurve curve = OcvCurve::lipo();  ///< the cells' open-circuit curve
  /// ohm; the resistance a pack file learned on earlier flights, where the least squares starts
  /// (with a third of it as its spread); NaN: none known, it starts from nothing.
  double initial_resistance_ohm = kNaN;
  /// V per cell a pack at rest stands above `curve` (a curve learned under the hover's load, the
  /// pack file's): taken off a resting voltage before it is read on the curve.
  double rest_offset_cell_v = 0.0;
  double rest_current_a = 3.0;  ///< A; below this the pack is at rest
  /// s; the internal resistance's recursive least squares forgets older samples with this time
  /// constant (the resistance grows as the pack empties and warms).
  double resistance_memory_s = 300.0;
  double voltage_sigma_v = 0.03;      ///< V; noise of one pack voltage reading
  double curve_sigma_cell_v = 0.015;  ///< V per cell; a pack's resting voltage off the curve
  double current_bias_a = 0.3;        ///< A; how far a current sensor may be off (drift of the count)
  /// How far the charge a pack gives may lie off its rating (age, cold), relative: a spread of
  /// the endurance no flight of a minute can narrow.
  double capacity_rel_std = 0.10;
  /// How far along the charge axis a pack's knee near empty may lie off the curve's (0..1): where
  /// the loaded cut-off falls, which no minute of hover above the knee shows.
  double knee_soc_std = 0.05;
  /// How much more than the resistance identified so far the hover may come to see, relative, on
  /// a pack's first minutes: the slow polarisation (minutes) builds after the least squares has
  /// settled. It fades as exp(-loaded time / polarisation_time_s). Enters the interval's low end.
  double polarisation_rel = 0.5;
  double polarisation_time_s = 300.0;  ///< s; how long the slow polarisation takes to build
  /// Share of the rated capacity a pack of unknown temperature may lack (a cold pack gives less):
  /// enters the interval's low end.
  double cold_capacity_rel = 0.08;
  /// The 90 % interval's ends in spreads below and above the central figure, calibrated on the
  /// battery family's development packs (test_hover_endurance_flight.cpp, docs/capability.md).
  ///@{
  double interval_low_z = 1.50;
  double interval_high_z = 0.86;
  ///@}
  /// A; the least change of current the resistance needs to be identified (a take-off gives it).
  double min_current_span_a = 2.0;
  double max_resistance_rel_std = 0.35;  ///< the resistance's standard deviation over it, at most
  double max_soc_std = 0.08;             ///< state of charge standard deviation (0..1), at most

  /// Throws FieldError naming the field (capability/battery/...): cells outside 1..14, a capacity or
  /// memory not positive, a sigma negative.
  void validate() const;
};

/// The pack's state after the last reading; NaN before any.
struct BatteryEstimate {
  double state_of_charge = kNaN;      ///< 0..1 of the rated capacity
  double state_of_charge_std = kNaN;  ///< including the curve's uncertainty
  /// ohm; what the current sags the pack by (over the least squares' memory: the series
  /// resistance and the part of the polarisation that builds within it).
  double internal_resistance_ohm = kNaN;
  double internal_resistance_std_ohm = kNaN;  ///< ohm; one standard deviation
  double open_circuit_voltage_v = kNaN;  ///< pack; the terminal voltage plus resistance x current
  double current_a = kNaN;               ///< the last current used (measured or given)
  double current_span_a = 0.0;           ///< A; largest minus smallest current seen
  /// s since the current first varied by min_current_span_a (the take-off); 0 before.
  double loaded_s = 0.0;
};

/// The pack's state of charge and internal resistance from its terminal voltage and current, O(1)
/// per reading, fixed memory. The resistance and the voltage the pack would rest at come from a
/// recursive least squares with forgetting of voltage against current (V = E - R I, as PX4's
/// battery estimator does), its E carried along the open-circuit curve as charge is drawn, R held
/// while the current stays steady (nothing tells it from E then); the state of charge from a Kalman filter that counts the charge drawn (coulomb counting) and is
/// corrected by the curve at the open-circuit voltage: the curve corrects the counter's drift, the
/// counter the curve's flat middle.
class BatteryEstimator {
 public:
  /// Throws FieldError for a bad config.
  explicit BatteryEstimator(BatteryEstimatorConfig config);

  /// One reading at `time_s`: terminal voltage in V, current drawn in A (its magnitude; NaN when
  /// not measured: no charge is counted and the resistance is not updated). A NaN or non-positive
  /// voltage, or a time not after the last, is ignored.
  void add(double time_s, double voltage_v, double current_a);
  /// A state of charge (0..1) reported by the autopilot as a share of the capacity, with its
  /// standard deviation: a measurement of the filter. NaN or outside 0..1 is ignored.
  void addStateOfCharge(double state_of_charge, double sigma);

  /// The state after the last reading.
  const BatteryEstimate& estimate() const { return estimate_; }
  /// Empty when the estimate has converged; otherwise why the figures resting on it are withheld.
  std::string withheldReason() const;
  /// The validated configuration.
  const BatteryEstimatorConfig& config() const { return config_; }

 private:
  void countCharge(double dt_s, double current_a);
  void updateResistance(double dt_s, double voltage_v, double current_a);
  void correctWithCurve(double open_circuit_v, double variance);
  void publish();

  BatteryEstimatorConfig config_;
  bool started_ = false;
  double last_s_ = 0.0;
  double last_current_a_ = kNaN;
  double min_current_a_ = kNaN, max_current_a_ = kNaN;
  double loaded_since_s_ = kNaN;  // when the current span first reached min_current_span_a
  double mean_current_a_ = 0.0;  // low-passed: a move off it excites R
  // State of charge and its variance.
  double soc_ = 0.0, soc_var_ = 0.0;
  // V = E - R I: offset E (V) and slope R (ohm) against -I.
  ForgettingLineFit fit_;
  BatteryEstimate estimate_;
};

}  // namespace propulsion_estimator
