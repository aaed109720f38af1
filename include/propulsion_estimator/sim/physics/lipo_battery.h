#pragma once

#include <string>
#include <vector>

namespace propulsion_estimator {
namespace sim {

/// Lithium-polymer pack as a first-order Thevenin equivalent circuit (G. Plett, Battery Management
/// Systems vol. 1, 2015, ch. 2): open-circuit voltage as a function of state of charge, a series
/// resistance, and one RC pair for the polarisation that builds up under load and relaxes after.
struct LipoBatteryParams {
  std::string name;  ///< for metadata and messages
  int cells = 0;  ///< in series
  double capacity_ah = 0.0;  ///< rated capacity, Ah
  /// Resting voltage of one cell at increasing states of charge (0..1), linearly interpolated.
  ///@{
  std::vector<double> ocv_soc;
  std::vector<double> ocv_cell_v;
  ///@}
  double series_resistance_ohm = 0.0;  ///< whole pack
  double rc_resistance_ohm = 0.0;  ///< ohm, of the polarisation RC pair
  double rc_capacitance_f = 0.0;  ///< F, of the polarisation RC pair

  /// Throws FieldError (battery.*): 1..14 cells, a table from soc 0 to 1 with rising voltages
  /// between 2.5 and 4.4 V per cell, positive resistances and capacity.
  void validate() const;

  double openCircuitVoltage(double state_of_charge) const;  ///< whole pack
};

/// A LipoBatteryParams pack in use: its state of charge and polarisation as current is drawn.
class LipoBattery {
 public:
  /// Throws FieldError("initial_soc") outside 0..1; validates the parameters.
  LipoBattery(LipoBatteryParams params, double initial_soc);

  /// The pack seen from its terminals: this EMF behind seriesResistanceOhm().
  double sourceVoltage() const;
  /// ohm, the pack's series resistance.
  double seriesResistanceOhm() const { return params_.series_resistance_ohm; }
  /// V at the terminals while drawing `current_a` (A, positive when discharging)
  double terminalVoltage(double current_a) const { return sourceVoltage() - seriesResistanceOhm() * current_a; }

  /// Draws `current_a` (positive when discharging) for `dt_s`: coulomb counting and the exact
  /// response of the RC pair to a constant current.
  void draw(double current_a, double dt_s);

  /// 0..1
  double stateOfCharge() const { return soc_; }
  /// V across the RC pair
  double polarisationVoltage() const { return polarisation_v_; }

 private:
  LipoBatteryParams params_;
  double soc_;
  double polarisation_v_ = 0.0;
};

}  // namespace sim
}  // namespace propulsion_estimator
