#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "propulsion_estimator/model/model_effects.h"
#include "propulsion_estimator/model/motor_reference.h"
#include "propulsion_estimator/model/rpm_thrust.h"
#include "propulsion_estimator/model/response_surface.h"

namespace propulsion_estimator {

/// The outputs of a propulsion model, in SI units when evaluated: thrust N, current A, power W,
/// efficiency N/W, rotor speed rpm.
enum class Output { kThrust = 0, kCurrent, kPower, kEfficiency, kRpm };
constexpr int kOutputCount = 5;  ///< number of Output values
static_assert(static_cast<int>(Output::kRpm) + 1 == kOutputCount, "kOutputCount counts every Output");
/// Every Output, in declaration order.
constexpr std::array<Output, kOutputCount> kAllOutputs = {Output::kThrust, Output::kCurrent, Output::kPower,
                                                          Output::kEfficiency, Output::kRpm};
/// "thrust", "current", ... as used for keys in model files and reports.
const char* outputName(Output output);

/// How an output is obtained: its own surface, derived from the others (efficiency = thrust /
/// power, power = voltage * current, current = power / voltage), or not modelled at all (a bench
/// without tachometer has no rpm), in which case it is reported as NaN.
enum class OutputSource { kSurface, kDerived, kNone };

/// How well a fitted surface matched its bench data (written by fit_surfaces, in the output's unit).
struct FitQuality {
  int pwm_degree = 0;          ///< PWM degree of the surface (a drive curve's degree in u)
  int voltage_degree = 0;      ///< voltage degree of the surface (a drive curve's degree in u)
  int points = 0;              ///< bench samples it was fitted on
  double r2 = 0.0;             ///< coefficient of determination
  double rmse = 0.0;           ///< root mean square error
  double max_error = 0.0;      ///< largest absolute error
  double held_out_rmse = 0.0;  ///< cross-validated, data grouped as `grouping` says
  std::string grouping;        ///< "voltage_level", "pwm_level" or "log"
  std::string basis = "polynomial";      ///< or "drive_curve"
  std::optional<double> low_band_rmse;   ///< fitted above the lowest voltage band, judged on it
  std::optional<double> high_band_rmse;  ///< fitted below the highest voltage band, judged on it
};

/// One output of a model file: its unit, how it is obtained (surface, derived, none) and the fit
/// that produced its surface.
struct OutputDefinition {
  std::string unit;  ///< unit of the surface values, as written in the file (g, N, A, W, g/W, rpm...)
  OutputSource source = OutputSource::kNone;  ///< surface, derived or none
  std::optional<ResponseSurface> surface;  ///< set iff source == kSurface
  std::string note;                        ///< why derived or absent; kept for the file's readers
  std::optional<FitQuality> fit;  ///< how the surface was fitted; absent for a hand-written one
};

/// Multiplier from a unit string to SI (N, A, W, N/W, rpm); nullopt when the unit does not fit
/// the output.
std::optional<double> unitToSi(Output output, const std::string& unit);

/// What evaluating a model does outside its domain: clamp the inputs to it, extrapolate the
/// surfaces, or compute nothing.
enum class OutsideDomain { kClamp, kExtrapolate, kReject };
/// "clamp", "extrapolate", "reject": as the model file spells the policy.
const char* outsideDomainName(OutsideDomain policy);

/// The voltage range the bench covered at one PWM level (us, V).
struct CoveredLevel {
  double pwm_us = 0.0;         ///< the level's PWM, us
  double voltage_min_v = 0.0;  ///< lowest voltage logged there, V
  double voltage_max_v = 0.0;  ///< highest voltage logged there, V
};

/// The inputs a model was measured over: ESC pulse width in us, supply voltage in V, and the
/// policy outside them. `covered`, when given, is where the bench went inside that box: per PWM
/// level (ascending) the voltage range logged there, linearly interpolated between levels (a
/// battery discharge never logs a high PWM at a low voltage, and a surface there is a guess). Old
/// model files have no `covered`: their domain is the box.
struct ModelDomain {
  double pwm_min_us = 0.0;                         ///< us
  double pwm_max_us = 0.0;                         ///< us
  double voltage_min_v = 0.0;                      ///< V
  double voltage_max_v = 0.0;                      ///< V
  OutsideDomain outside = OutsideDomain::kClamp;  ///< what evaluating does outside the domain
  std::vector<CoveredLevel> covered;               ///< empty: the box is the domain

  /// The voltage range covered at `pwm_us` (clamped to the PWM range): the box's without `covered`.
  std::pair<double, double> voltageRange(double pwm_us) const;
  /// Whether (us, V) lies in the box and, with `covered`, in the covered voltage range at that PWM.
  bool contains(double pwm_us, double voltage_v) const;
  /// Into the domain: the PWM clamped to its range; a voltage beyond the box's to the nearest bound
  /// at the same drive ((PWM - pwm_min_us) x voltage, what the motor sees through the ESC's duty),
  /// the PWM moving with it within its range; then to the voltage logged nearest at that PWM.
  /// Returns the factor on the battery current, the same power at the supply's voltage: the bound's
  /// voltage over the supply's (1 within the box's voltages).
  double clamp(double* pwm_us, double* voltage_v) const;
  /// Throws ConfigError naming the field for an empty box or a `covered` whose levels are not
  /// ascending, outside the box, or with an empty voltage range.
  void validate() const;
};

/// What fed the ESC on the bench: a regulated supply or a battery.
enum class SupplyKind { kRegulated, kBattery };
/// "regulated", "battery": as the model file spells the supply.
const char* supplyKindName(SupplyKind supply);

/// Where a model comes from: the ESC, motor and propeller names, the bench air (deg C, Pa) and
/// supply, and the source of the data.
struct ModelMetadata {
  std::string esc;  ///< the ESC's name
  std::string motor;  ///< the motor's name
  std::string propeller;  ///< the propeller's name
  /// Air on the bench, both or neither: a model whose bench air is unknown estimates as well,
  /// but cannot be corrected for the flight air's density (the air_density effect).
  std::optional<double> bench_air_temperature_c;
  std::optional<double> bench_air_pressure_pa;  ///< Pa; see bench_air_temperature_c
  SupplyKind supply = SupplyKind::kRegulated;  ///< what fed the ESC on the bench
  std::string source;  ///< the bench data the model was fitted on

  /// Whether both bench air values are known.
  bool hasBenchAir() const { return bench_air_temperature_c && bench_air_pressure_pa; }
  /// Air density on the bench, p / (R T), kg/m^3: the reference of the air_density effect; NaN
  /// without bench air.
  double benchAirDensity() const;
  /// FieldError ("metadata.bench_air_temperature_c", ...) for bench air outside the ranges the
  /// model loader accepts, or only one of the two given; fit_surfaces applies the same check
  /// before it writes a model.
  void validate() const;
};

/// Steady-state operating point of one motor from the surfaces, in SI units.
struct OperatingPoint {
  double thrust_n = 0.0;  ///< N
  double current_a = 0.0;  ///< A
  double power_w = 0.0;  ///< W
  double efficiency_n_per_w = 0.0;  ///< N/W
  double rpm = 0.0;  ///< rpm
  bool in_domain = false;  ///< false when the inputs lay outside the domain (clamped or extrapolated)
};

/// The response surfaces of one ESC-motor-propeller combination, and the effects measured in
/// flight that they leave out (the model file's optional `effects:` section).
class PropulsionModel {
 public:
  /// Throws ConfigError (without file context) for a unit that does not fit its output, a
  /// derivation that is circular or refers to an absent output, thrust not modelled, or an
  /// empty domain; FieldError ("effects.<name>.<key>") for effects that ModelEffects::validate()
  /// refuses, and for air_density on a thrust surface not finite and above zero at fullThrustN()'s point. The
  /// effects' references from the model (bench air density, full thrust) are the model's, whatever
  /// `effects` says.
  PropulsionModel(ModelMetadata metadata, ModelDomain domain, std::array<OutputDefinition, kOutputCount> outputs,
                  effects::ModelEffects effects = {});

  /// The same surfaces with other effects (a corrected model); throws as the constructor does.
  PropulsionModel withEffects(effects::ModelEffects effects) const;

  /// Evaluates all outputs. Outside the domain the inputs are clamped (ModelDomain::clamp; the
  /// battery current then scaled to the same power at the supply's voltage), or the surfaces
  /// extrapolated, as the model says, and in_domain is false; with the reject policy nothing is
  /// computed and false is returned. Thrust, current, power and rpm are floored at zero (an idling
  /// polynomial may dip below it); efficiency is zero where power is zero.
  bool evaluate(double pwm_us, double voltage_v, OperatingPoint* estimate) const;

  /// One output in its file unit at any point, without clamping to the domain: a surface's own
  /// value (not floored), a derived output as evaluate() derives it, NaN if not modelled.
  double evaluateRaw(Output output, double pwm_us, double voltage_v) const;

  /// The thrust surface at the domain's highest pulse width and the highest voltage logged there, N:
  /// the scale of air_density's law.
  double fullThrustN() const;

  /// The ESC, motor, propeller, bench air and supply.
  const ModelMetadata& metadata() const { return metadata_; }
  /// The inputs the surfaces were measured over.
  const ModelDomain& domain() const { return domain_; }
  /// One output's unit, source and surface.
  const OutputDefinition& output(Output output) const { return outputs_[static_cast<int>(output)]; }
  /// What the surfaces leave out; evaluate() does not apply it (the Estimator does, with the
  /// signals the effects read).
  const effects::ModelEffects& effects() const { return effects_; }
  /// Thrust against measured rpm (the model file's optional thrust_from_rpm, fitted by
  /// fit_surfaces from the bench logs' rpm column); nullopt when the file has none.
  const std::optional<RpmThrust>& rpmThrust() const { return rpm_thrust_; }
  /// Sets or clears it.
  void setRpmThrust(std::optional<RpmThrust> rpm_thrust) { rpm_thrust_ = rpm_thrust; }
  /// The vehicle's healthy per-motor fingerprint (the model file's optional motor_reference,
  /// written by diagnose_gap --reference): the node's motor-health check and later diagnoses judge
  /// each motor's change from it; nullopt when the file has none.
  const std::optional<MotorReference>& motorReference() const { return motor_reference_; }
  /// Sets or clears it; throws FieldError as MotorReference::validate() does. With the reference's
  /// air density set, air_density's effect reads the air as a change from that air (the thrust
  /// level the reference folded into the corrected model was flown in it), else from the bench's.
  void setMotorReference(std::optional<MotorReference> reference);

 private:
  /// ModelEffects::validate() and the full thrust air_density reads; throws FieldError.
  void validateEffects(const effects::ModelEffects& effects) const;
  /// All outputs in SI, floored as evaluate() documents, in dependency order.
  std::array<double, kOutputCount> computeSi(double pwm_us, double voltage_v) const;
  double evaluateSi(Output output, double pwm_us, double voltage_v, const std::array<double, kOutputCount>& done) const;

  ModelMetadata metadata_;
  ModelDomain domain_;
  std::array<OutputDefinition, kOutputCount> outputs_;
  effects::ModelEffects effects_;
  std::optional<RpmThrust> rpm_thrust_;
  std::optional<MotorReference> motor_reference_;
  std::array<double, kOutputCount> to_si_{};
  std::array<Output, kOutputCount> evaluation_order_{};
};

}  // namespace propulsion_estimator
