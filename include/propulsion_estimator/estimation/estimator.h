#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "propulsion_estimator/common/input_signal.h"
#include "propulsion_estimator/estimation/barometric_vertical_speed.h"
#include "propulsion_estimator/estimation/estimator_config.h"
#include "propulsion_estimator/estimation/hover_detector.h"
#include "propulsion_estimator/estimation/payload_estimator.h"
#include "propulsion_estimator/model/model_effects.h"
#include "propulsion_estimator/model/propulsion_model.h"
#include "propulsion_estimator/vehicle/vehicle.h"
#include "propulsion_estimator/estimation/vertical_acceleration_filter.h"

namespace propulsion_estimator {

/// Why an input was not used. Every refused message is counted and leaves the estimates as they
/// were: nothing is computed from it.
enum class Rejection {
  kNone = 0,
  kBadVoltage,      ///< battery voltage NaN, infinite, zero or negative
  kBadImu,          ///< non-finite or non-unit orientation, non-finite acceleration
  kBadVelocity,     ///< non-finite vertical speed or horizontal velocity
  kNoBattery,       ///< motor outputs before any valid voltage
  kStaleBattery,    ///< newest valid voltage older than battery_timeout_s
  kDisarmed,        ///< a motor at or below disarmed_pwm_max_us (0, 900 us, ...)
  kTooFewChannels,  ///< RCOut shorter than the highest motor channel
  kTimeBackwards,   ///< RCOut stamp older than the previous accepted one
  kStampAhead,      ///< RCOut stamped more than max_stamp_ahead_s ahead of its receipt
  kDuplicate,       ///< RCOut with the stamp of the previous accepted one: the same message again
  kOutsideDomain,   ///< outside the model's domain and the model says reject
  kNonFiniteEstimate,  ///< the model gives NaN or infinity (a rational surface extrapolated to its pole)
                       ///< for an output it has; one it lacks (`none`) is NaN and not refused
  /// Signals of the model's effects, refused outside what the quantity can be (a unit error):
  kBadBatteryCurrent,   ///< infinite, or more than 1000 A either way
  /// A scalar input outside its ScalarSpec's min..max, or NaN; a range outside its message's own
  /// min_range..max_range (RejectionDetail::input says which input).
  kBadInput,
};
constexpr int kRejectionCount = 15;  ///< number of Rejection values
static_assert(static_cast<int>(Rejection::kBadInput) + 1 == kRejectionCount, "kRejectionCount counts every Rejection");
/// "bad_voltage", "stale_battery", ...: the name of a rejection in diagnostics and counters
/// ("bad_input" for any scalar input: badInputName names which).
const char* rejectionName(Rejection rejection);
/// "bad_air_temperature": the name of a refused reading of `scalar` in diagnostics and counters.
std::string badInputName(input::Scalar scalar);

/// The last refusal with what it was about, turned into text only when someone asks.
struct RejectionDetail {
  Rejection reason = Rejection::kNone;  ///< the last refusal's reason (kNone before any)
  int channel = 0;     ///< 1-based, for kDisarmed
  double value = 0.0;  ///< offending value (voltage, PWM, channel count, seconds)
  double limit = 0.0;  ///< what it was checked against
  double limit_high = 0.0;  ///< upper end where the check is a range (kBadInput)
  input::Scalar input = input::Scalar::kStaticPressure;  ///< the refused input, for kBadInput
};
/// One line for diagnostics: the rejection with its channel, value and limit ("none" for kNone).
std::string describe(const RejectionDetail& detail);

/// One motor's estimate for the last accepted RCOut message: its channel (1-based), pulse width in
/// us and the model's operating point (SI units) with the effects applied.
struct MotorOutput {
  int channel = 0;  ///< RCOut channel, 1-based
  double pwm_us = 0.0;  ///< the pulse width the channel carried, us
  OperatingPoint estimate;  ///< thrust N, current A, power W, efficiency N/W, rpm, in_domain
};

/// The vehicle's totals over all motors, SI units: summed thrust and its vertical part, current
/// and power, and the mass they lift (vertical thrust over g plus the vertical acceleration).
/// Current, power and efficiency are NaN when the model lacks them (see unmodelledOutputs()).
struct Totals {
  double voltage_v = 0.0;  ///< battery voltage the motors were evaluated at, V
  double thrust_n = 0.0;  ///< summed thrust along the rotor axes, N
  double vertical_thrust_n = 0.0;  ///< the vertical part of the thrust, N (tilt-compensated while the IMU is fresh)
  double current_a = 0.0;  ///< summed current, A
  double power_w = 0.0;  ///< summed electrical power, W
  double efficiency_n_per_w = 0.0;  ///< thrust over power, N/W
  double mass_kg = 0.0;  ///< the mass the vertical thrust lifts, kg
  double thrust_centre_x_m = 0.0;  ///< NaN without vehicle geometry
  double thrust_centre_y_m = 0.0;  ///< NaN without vehicle geometry
  int motors_out_of_domain = 0;  ///< motors whose PWM or voltage lay outside the model's domain
};

/// Where the hover detector's vertical speed came from: the velocity topic, the barometer's height
/// rate when no velocity is fresh, or nowhere (the vertical speed check is inactive).
enum class VerticalSpeedSource { kNone, kVelocity, kBarometer };
/// "none", "velocity", "barometer".
const char* verticalSpeedSourceName(VerticalSpeedSource source);

/// Everything the estimator computed for the last accepted RCOut message; `stamp_s` is its header
/// time in s.
struct EstimatorOutput {
  double stamp_s = 0.0;  ///< the message's header time, s (its receipt time when unstamped)
  std::vector<MotorOutput> motors;  ///< sized once, one per rotor
  Totals totals;  ///< over all motors
  /// The model's effects not applied to this message because their signal was missing or stale.
  effects::KindMask effects_skipped = 0;
  HoverVerdict hover;  ///< the hover detector's verdict after this message
  /// Where the hover check's vertical speed came from.
  VerticalSpeedSource vertical_speed_source = VerticalSpeedSource::kNone;
  MassEstimate payload;  ///< total, empty and payload mass
};

/// Counts of the inputs accepted and rejected (by Rejection) since start, and of the motor samples
/// and effects applied, for diagnostics.
struct EstimatorCounters {
  std::array<std::uint64_t, kRejectionCount> rejected{};  ///< refused inputs, indexed by Rejection
  input::PerScalar<std::uint64_t> rejected_inputs{};  ///< of rejected[kBadInput], by input::index
  std::uint64_t accepted = 0;  ///< RCOut messages accepted
  std::uint64_t motor_samples = 0;  ///< motor estimates computed (accepted messages times motors)
  std::uint64_t motor_samples_outside_domain = 0;  ///< of which outside the model's domain
  std::uint64_t clock_resets = 0;  ///< times the clock went back (a bag restarted) and everything was reset
  /// Accepted messages on which each of the model's effects was applied, or skipped (its signal
  /// missing or stale), indexed by effects::Kind.
  std::array<std::uint64_t, effects::kKindCount> effect_applied{};
  std::array<std::uint64_t, effects::kKindCount> effect_skipped{};  ///< see effect_applied
};

/// Answer of tare(): the new empty mass, or why there is none.
struct TareResult {
  bool ok = false;  ///< whether the empty mass was recorded
  double empty_mass_kg = 0.0;  ///< the new empty mass, kg
  std::string message;  ///< why the tare was refused, or what was recorded
};

/// The whole onboard estimation, free of ROS: inputs in, estimates out. `receipt_s` is the time
/// an input arrived on the estimator's clock (ROS time, simulated when replaying a bag); it drives
/// staleness. Stamps are the inputs' own header times. Evaluating motor outputs allocates nothing.
///
/// The model's effects (effects::ModelEffects) are applied to every motor: the surfaces are
/// evaluated at effects::correctInputs() and thrust and efficiency multiplied by
/// effects::thrustFactor() at each rotor's own thrust (floored at zero, as the surfaces' thrust is). A correction whose signal
/// is missing or older than its timeout is skipped for that message and counted.
class Estimator {
 public:
  /// Throws ConfigError if the configuration does not fit the vehicle.
  Estimator(PropulsionModel model, Vehicle vehicle, EstimatorConfig config);

  /// Battery voltage in V, received at `receipt_s` (s); kBadVoltage for NaN, infinite, zero or negative.
  Rejection addBattery(double receipt_s, double voltage_v);
  /// Orientation rotates body into the world (ENU); acceleration is the IMU's specific force in
  /// the body frame (about +9.81 m/s^2 on z at rest), as MAVROS publishes them.
  Rejection addImu(double receipt_s, const Eigen::Quaterniond& orientation, const Eigen::Vector3d& specific_force);
  /// Vertical speed in m/s (ENU, up positive); kBadVelocity when not finite.
  Rejection addVerticalSpeed(double receipt_s, double vertical_speed_m_s);
  /// Horizontal velocity over the ground in m/s (the local velocity's x east, y north, ENU), for
  /// the effects that read it; kBadVelocity when not finite. Used until velocity_timeout_s.
  Rejection addHorizontalVelocity(double receipt_s, double east_m_s, double north_m_s);

  /// Signals of the model's effects; each is used until its timeout (EstimatorConfig).
  /// Battery current as the autopilot reports it: its magnitude is the current drawn, since the
  /// sign conventions differ (sensor_msgs/BatteryState and PX4's MAVROS: negative when
  /// discharging) and a flying multicopter only discharges. NaN is BatteryState's "not measured":
  /// ignored, not refused. Ages like the voltage (battery_timeout_s).
  Rejection addBatteryCurrent(double receipt_s, double current_a);
  /// A reading of the scalar input `scalar` in its ScalarSpec's unit; kBadInput when NaN or
  /// outside the spec's min..max. Used until its timeout (EstimatorConfig::input_timeout_s). Static
  /// pressure and air temperature give the air density p / (R T); the static pressure's height
  /// rate is also the hover check's vertical speed while no velocity is fresh. A range given here
  /// is a valid reading (a log keeps only those); +inf is out of ground effect.
  Rejection addInput(input::Scalar scalar, double receipt_s, double value);
  /// A downward rangefinder's sensor_msgs/Range (m), REP-117: kBadInput for NaN or a finite range
  /// outside the message's min_range..max_range; +inf (nothing within max_range) is out of ground
  /// effect, -inf (closer than min_range) is taken as min_range, the farthest the ground can then
  /// be, so that the correction is never overdone. The height is the range times the cosine of
  /// the tilt while the IMU is fresh.
  Rejection addRange(double receipt_s, double range_m, double min_range_m, double max_range_m);
  /// The signals as the corrections read them at `now_s`: NaN where missing or stale. Prepared
  /// by effects::prepareSignals, as the gap diagnosis prepares its flights' (effect_signals.h).
  effects::Signals effectSignals(double now_s) const;

  /// One RCOut message: PWM of all channels (0-based array of the message's channels). Returns
  /// kNone and fills output(), or the reason nothing was computed.
  Rejection addMotorOutputs(double stamp_s, double receipt_s, const std::uint16_t* channels, std::size_t count);

  /// The last accepted message's estimates.
  const EstimatorOutput& output() const { return output_; }
  /// Counts since start.
  const EstimatorCounters& counters() const { return counters_; }
  /// The last refusal and its values.
  const RejectionDetail& lastRejection() const { return last_rejection_; }
  /// Seconds since the newest valid voltage at `now_s`; infinity before any.
  double batteryAge(double now_s) const;

  /// Records the current hover average as the empty mass, or refuses when not hovering at `now_s`
  /// (the estimator's clock), which includes a hover verdict expired by expireHover().
  TareResult tare(double now_s);
  /// A hover verdict older than its window is no verdict: when no motor output was accepted within
  /// hover/window_s before `now_s`, the hover window is forgotten (verdict kExpired) and the payload
  /// holds its average, not hovering. Every input calls it; call it before reading the verdict when
  /// inputs may have stopped (services, diagnostics).
  void expireHover(double now_s);
  /// Switches the model's effect `kind` on with `value` (its ParameterSpec unit, clamped to its
  /// range) or off (nullopt), from the next motor output on: an effect estimated in flight (the
  /// live model check's supply resistance). Copies the model's surfaces (allocates).
  void setEffect(effects::Kind kind, std::optional<double> value);
  /// Sets the empty mass from elsewhere (a tare file, a parameter, the URDF).
  void setEmptyMass(double mass_kg, EmptyMassSource source);
  /// Clears the windows and the tare; the configured empty mass (parameter or URDF) applies again.
  void reset();
  std::string describeHover() const;  ///< the hover verdict as one line, describe(HoverVerdict, HoverConfig)

  /// The model, with its effects.
  const PropulsionModel& model() const { return model_; }
  /// The vehicle's rotors and mass properties.
  const Vehicle& vehicle() const { return vehicle_; }
  /// As validated.
  const EstimatorConfig& config() const { return config_; }

 private:
  /// The latest valid reading of one signal and when it arrived.
  struct Reading {
    double value = 0.0;
    double receipt_s = 0.0;
    bool have = false;

    void set(double receipt, double v) {
      value = v;
      receipt_s = receipt;
      have = true;
    }
    /// NaN when missing or older than `timeout_s` at `now_s`.
    double at(double now_s, double timeout_s) const;
  };

  Rejection reject(Rejection reason, int channel = 0, double value = 0.0, double limit = 0.0,
                   double limit_high = 0.0);
  Rejection rejectInput(input::Scalar scalar, double value, double limit, double limit_high);
  void checkClock(double receipt_s);
  bool imuFresh(double now_s) const;
  bool velocityFresh(double now_s) const;
  void clearWindows();
  /// addMotorOutputs' steps, in order; the checks return kNone or what refused the message.
  /// This one refuses a message without a fresh voltage, with too few channels or a motor disarmed.
  Rejection checkBatteryAndChannels(double receipt_s, const std::uint16_t* channels, std::size_t count);
  /// Takes an unstamped message as stamped on arrival; refuses stamps ahead, repeated or back in time.
  Rejection checkStamp(double receipt_s, double* stamp_s);
  /// Every motor into scratch_, with the effects' corrections; nothing committed on a refusal.
  Rejection evaluateMotors(double receipt_s, const std::uint16_t* channels, effects::KindMask* skipped);
  /// Commits scratch_ to output_.motors and sums it into the totals.
  Totals sumMotors(const std::uint16_t* channels, bool imu_fresh, double vertical_accel);
  /// What the hover detector judges: the totals, the tilt and the freshest vertical speed.
  HoverSample hoverSample(const Totals& totals, double receipt_s, bool imu_fresh, double vertical_accel,
                          VerticalSpeedSource* speed_source) const;
  /// Counts an accepted message and the effects it applied or skipped.
  void countAccepted(double stamp_s, double receipt_s, const Totals& totals, effects::KindMask skipped);

  PropulsionModel model_;
  Vehicle vehicle_;
  EstimatorConfig config_;
  std::optional<double> configured_empty_mass_kg_;
  EmptyMassSource configured_source_ = EmptyMassSource::kNone;

  HoverDetector hover_;
  PayloadEstimator payload_;
  VerticalAccelerationFilter accel_filter_;
  BarometricVerticalSpeed barometric_speed_;
  /// Which outputs the model has: one it lacks is published as NaN, never refused as non-finite.
  bool has_current_;
  bool has_power_;
  bool has_efficiency_;

  double voltage_v_ = 0.0;
  double voltage_receipt_s_ = 0.0;
  bool have_voltage_ = false;
  Eigen::Matrix3d body_to_world_ = Eigen::Matrix3d::Identity();
  double imu_receipt_s_ = 0.0;
  bool have_imu_ = false;
  double vertical_speed_m_s_ = 0.0;
  double velocity_east_m_s_ = kNaN;
  double velocity_north_m_s_ = kNaN;
  double horizontal_receipt_s_ = -std::numeric_limits<double>::infinity();
  double velocity_receipt_s_ = 0.0;
  bool have_velocity_ = false;
  Reading battery_current_a_;
  input::PerScalar<Reading> inputs_;
  double last_stamp_s_ = 0.0;
  bool have_stamp_ = false;
  double last_receipt_s_ = 0.0;
  double last_accepted_receipt_s_ = 0.0;  ///< when the newest accepted motor output arrived
  bool have_accepted_ = false;

  std::vector<OperatingPoint> scratch_;  ///< this message's motors, committed to output_ once all are valid
  EstimatorOutput output_;
  EstimatorCounters counters_;
  RejectionDetail last_rejection_;
};

}  // namespace propulsion_estimator
