#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/estimation/estimator.h"
#include "propulsion_estimator/onboard/esc_report.h"
#include "propulsion_estimator/onboard/supply_resistance_estimator.h"

namespace propulsion_estimator {

/// How the live model check judges ESC telemetry against the model (parameters esc_telemetry/*).
struct ModelCheckConfig {
  /// s; a motor whose last new ESC report is older than this (receipt time) has no measurement:
  /// NaN on ~motors, left out of the averages. Also the age beyond which the RCOut the
  /// measurement is compared with is too old.
  double stale_after_s = 0.5;
  /// s; time constant of the hover averages of the measured-to-modelled ratios.
  double window_s = 3.0;
  /// s of hover with fresh telemetry every motor needs before the motors are judged.
  double min_hover_s = 3.0;
  /// A motor's rpm ratio this far (relative) from the other motors' median is off; its current
  /// for that speed (MotorCheck::current_deviation) must then be off the other way by
  /// current_tolerance to name a cause.
  double rpm_tolerance = 0.009;
  double current_tolerance = 0.01;  ///< see rpm_tolerance
  /// All motors' median rpm ratio this far (relative) from 1, with no motor off on its own: the
  /// supply (or anything else every motor shares).
  double supply_tolerance = 0.02;
  /// s; how long the supply resistance's least squares remembers.
  double supply_memory_s = 60.0;
  /// V; noise of one drop from the battery's terminals to the ESCs (power module and ESC dividers).
  double supply_voltage_sigma_v = 0.04;
  /// The supply resistance's standard deviation over its value, at most, before it is reported
  /// as estimated (and, with apply_supply_resistance, applied).
  double supply_max_rel_std = 0.2;
  /// Apply the estimated supply resistance as the model's supply_resistance effect.
  bool apply_supply_resistance = false;

  /// Throws FieldError naming the field (esc_telemetry/...) for a time or tolerance not positive,
  /// or supply_max_rel_std outside 0..1.
  void validate() const;
};

/// What the check says of one motor, or of the whole vehicle.
enum class ModelCheckVerdict {
  kNotJudged,  ///< too little hover with fresh telemetry yet
  kConsistent,  ///< measurements agree with the model
  kPropeller,  ///< rpm high, current low against the others: a damaged or wrong propeller
  kMotorEsc,   ///< rpm low, current high against the others: a weak motor (bearing, magnets) or ESC
  kSupply,     ///< every motor alike off the model: supply voltage (leads, connectors) or the air
};
/// "not_judged", "consistent", "propeller", "motor_esc", "supply".
const char* modelCheckVerdictName(ModelCheckVerdict verdict);
/// What a user does about `verdict`, one sentence.
const char* modelCheckAdvice(ModelCheckVerdict verdict);

/// One motor: its latest measurement beside the model, and its hover averages.
struct MotorCheck {
  int channel = 0;  ///< RCOut channel, 1-based
  double measured_rpm = kNaN;  ///< rpm, NaN when absent or stale
  double measured_current_a = kNaN;  ///< A, NaN when absent or stale
  double rpm_ratio = kNaN;  ///< measured over modelled, latest; NaN when either is missing
  double current_ratio = kNaN;  ///< see rpm_ratio
  double hover_rpm_ratio = kNaN;  ///< hover average of rpm_ratio
  double hover_current_ratio = kNaN;  ///< hover average of current_ratio
  double hover_s = 0.0;  ///< s of hover the averages hold
  /// The rpm average relative to the median of all motors' (0 = like the others), and against
  /// the baseline's where one is set (0 = as on the healthy flights).
  double rpm_deviation = kNaN;
  /// The current for the speed the motor turns at (the current ratio over the rpm ratio cubed:
  /// shaft power ~ n^3), relative to the median of all motors'. A propeller that needs less
  /// torque draws less for its speed; a command or model error moves speed and current together.
  double current_deviation = kNaN;
  ModelCheckVerdict verdict = ModelCheckVerdict::kNotJudged;  ///< this motor's family of cause
};

/// The whole check at one instant.
struct ModelCheckReport {
  std::vector<MotorCheck> motors;  ///< in rotor order
  int fresh_motors = 0;  ///< motors with fresh telemetry
  bool telemetry_seen = false;  ///< any ESC report since start
  ModelCheckVerdict verdict = ModelCheckVerdict::kNotJudged;  ///< the vehicle's: the worst motor's, or kSupply
  int flagged_channel = 0;  ///< the channel of the motor off on its own (0: none)
  double median_rpm_ratio = kNaN;  ///< over the motors' hover averages
  double median_current_ratio = kNaN;  ///< see median_rpm_ratio
  double supply_resistance_ohm = kNaN;  ///< estimated between battery and ESCs; NaN before any
  double supply_resistance_std_ohm = kNaN;  ///< one standard deviation
  bool supply_resistance_estimated = false;  ///< std within supply_max_rel_std of the value
  std::string note;  ///< why not judged, or what was found, one line
};

/// The live model check (issue 21): ESC telemetry's measured rpm and current per motor against the
/// model's at the same PWM and voltage. Over the hover window, a motor that turns faster and draws
/// less than the others (relative to the model) has a damaged propeller, one that turns slower and
/// draws more a weak motor or ESC; all alike off the model point at the supply. The resistance
/// between the battery and the ESCs comes from the battery's voltage against the ESCs' (least
/// squares with forgetting). Fixed memory (sized at construction), O(motors) per message.
class ModelCheck {
 public:
  /// `channels`: the RCOut channel of each rotor (1-based); ESC i reports on channel i + 1.
  /// Throws FieldError for a bad config.
  ModelCheck(std::vector<int> channels, ModelCheckConfig config);

  /// One ESC telemetry message received at `receipt_s`. A report repeating its ESC's previous one
  /// (the same count; or, without counts, the same values) is not a measurement and is skipped;
  /// reports of ESCs that drive no rotor are ignored.
  void addTelemetry(double receipt_s, const EscTelemetry& message);
  /// The estimator's output after an accepted RCOut received at `receipt_s`: the modelled rpm and
  /// current the next reports are compared with, and whether the vehicle hovers.
  void addEstimate(double receipt_s, const EstimatorOutput& output);
  /// The battery's terminal voltage (V) at `receipt_s`: with every motor's fresh ESC voltage and
  /// current, one sample of the supply resistance.
  void addBattery(double receipt_s, double voltage_v);
  /// Judges each motor by its change from a healthy baseline (MotorReference's esc_rpm_deviation
  /// and esc_current_deviation, one per rotor): healthy motors differ by their parts, as much as
  /// the tolerances. Empty lists: against the other motors alone. `rpm_level` (esc_rpm_level):
  /// the motors' median rpm against the model on those flights, which the supply verdict judges
  /// its change from (NaN: from 1). Throws std::invalid_argument when the lists are not both empty
  /// or both one per rotor, or for a level not positive. Survives reset().
  void setBaseline(std::vector<double> rpm_deviation, std::vector<double> current_deviation,
                   double rpm_level = kNaN);
  /// Forgets every average and the supply resistance.
  void reset();

  /// The check at `now_s` (staleness judged there).
  ModelCheckReport report(double now_s) const;
  /// Rotor `k`'s measurement and averages at `now_s`, without the verdicts (which need every
  /// motor); allocates nothing, for every published ~motors.
  MotorCheck motor(std::size_t k, double now_s) const;
  /// The estimated supply resistance, ohm, once within supply_max_rel_std; NaN before.
  double supplyResistanceOhm() const;
  /// The configuration the check was made with.
  const ModelCheckConfig& config() const { return config_; }

 private:
  struct Motor {
    int channel = 0;
    double modelled_rpm = kNaN, modelled_current_a = kNaN;
    EscReport last;  ///< the newest new report
    double last_receipt_s = kNaN;  ///< when it arrived
    double rpm_ratio = kNaN, current_ratio = kNaN;
    double log_rpm = 0.0, log_current = 0.0;  ///< hover averages of the log ratios
    double log_current_at_speed = 0.0;  ///< of the current ratio over the rpm ratio's cube
    double hover_s = 0.0;
    long averaged = 0;  ///< reports in the averages
    double averaged_at_s = kNaN;  ///< receipt time of the last report averaged
  };
  bool isNew(const Motor& motor, const EscReport& report) const;
  void compare(Motor* motor, double receipt_s);

  ModelCheckConfig config_;
  std::vector<Motor> motors_;
  std::vector<int> esc_to_motor_;  ///< rotor index of ESC i, -1 for none
  std::vector<double> baseline_log_rpm_, baseline_log_current_;  ///< per rotor; empty: no baseline
  double baseline_rpm_level_ = 1.0;  ///< the healthy flights' median rpm against the model
  double estimate_receipt_s_ = kNaN;
  bool hovering_ = false;
  bool telemetry_seen_ = false;
  SupplyResistanceEstimator supply_;
};

}  // namespace propulsion_estimator
