#pragma once

#include <string>
#include <vector>

namespace propulsion_estimator {

/// One cell's open-circuit (resting) voltage against its state of charge, linearly interpolated
/// between table points: the built-in LiPo and Li-ion curves or a table the user gives
/// (capability/battery/ocv_table). Built once at start; its queries allocate nothing.
class OcvCurve {
 public:
  /// The usual LiCoO2-polymer resting-voltage chart of RC practice: 3.27 V empty, 4.20 V full.
  static OcvCurve lipo();
  /// A graphite/NMC 18650-type Li-ion cell: 3.00 V empty, 4.19 V full.
  static OcvCurve liIon();
  /// "lipo" or "li_ion"; throws FieldError naming `field` for another name.
  static OcvCurve named(const std::string& chemistry, const std::string& field);
  /// A table of states of charge (0..1, from 0 to 1, increasing) and cell voltages in V (2.0..4.5 V,
  /// increasing). Throws FieldError naming `field` and the offending value.
  OcvCurve(std::vector<double> soc, std::vector<double> cell_v, const std::string& field);

  /// Cell voltage in V at `state_of_charge` (clamped to 0..1).
  double cellVoltage(double state_of_charge) const;
  /// dV/dSoC in V per unit state of charge at `state_of_charge` (the segment's slope).
  double slope(double state_of_charge) const;
  /// The state of charge (0..1) whose voltage is `cell_v`, clamped to the table's ends.
  double stateOfCharge(double cell_v) const;
  double emptyCellV() const { return cell_v_.front(); }  ///< V at 0 % charge
  double fullCellV() const { return cell_v_.back(); }    ///< V at 100 % charge
  const std::vector<double>& socTable() const { return soc_; }      ///< the table's states of charge
  const std::vector<double>& cellVTable() const { return cell_v_; }  ///< the table's V per cell

 private:
  std::size_t segment(double state_of_charge) const;

  std::vector<double> soc_;
  std::vector<double> cell_v_;
};

}  // namespace propulsion_estimator
