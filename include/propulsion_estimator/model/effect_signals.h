#pragma once

#include <string>

#include "propulsion_estimator/common/input_signal.h"
#include "propulsion_estimator/common/mavros_topics.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/model/model_effects.h"

/// @file
/// The one preparation of the effects' signals, shared by the node (estimation::Estimator) and the
/// gap diagnosis (gap::cutIntoBlocks): a parameter fitted by the diagnosis means on the vehicle
/// what it meant in the fit only if both turn the same readings into the same signals.
namespace propulsion_estimator {
namespace effects {

/// The readings an effect's signal is prepared from, as received or logged, SI units; NaN where a
/// reading is missing or stale.
struct RawSignals {
  double battery_current_a = kNaN;    ///< A, as the autopilot reports it: either sign
  /// Each scalar input in its ScalarSpec's unit (a range along the body's -z axis, +inf beyond
  /// the sensor's reach), by input::index.
  input::PerScalar<double> inputs = input::perScalar(kNaN);
  double body_z_up = 1.0;             ///< vertical component of the body's z axis (cos tilt); 1 without attitude
  double body_z_east = 0.0;           ///< east component of the body's z axis; 0 without attitude
  double body_z_north = 0.0;          ///< north component of the body's z axis; 0 without attitude
  double vertical_speed_m_s = kNaN;   ///< m/s, up positive
  double velocity_east_m_s = kNaN;    ///< m/s, local velocity x (ENU)
  double velocity_north_m_s = kNaN;   ///< m/s, local velocity y (ENU)

  /// The reading of the scalar input `scalar`.
  double& input(input::Scalar scalar) { return inputs[input::index(scalar)]; }
  /// The reading of the scalar input `scalar`.
  double input(input::Scalar scalar) const { return inputs[input::index(scalar)]; }
};

/// Dry air's density from static pressure and air temperature, rho = p / (R (T + 273.15)), kg/m^3:
/// the flight's air and the bench's alike. NaN when either is NaN. Does not throw.
double airDensityKgM3(double static_pressure_pa, double air_temperature_c);

/// The battery's discharge current, A, from a reading of either sign: MAVROS passes the
/// autopilot's sign on (PX4's arrives negative while discharging, ArduPilot's positive) and a
/// multicopter in flight only discharges, so the magnitude is the discharge current whatever the
/// autopilot. NaN stays NaN. Does not throw.
double dischargeCurrentA(double reported_a);

/// Height of the rangefinder above flat ground, m: the range along the body's -z axis times the
/// cosine of the tilt (`body_z_up`). NaN when the range is NaN or the vehicle is tilted 90 deg or
/// more (the sensor sees no ground); +inf stays +inf (no ground within reach: far). Does not throw.
double heightAboveGroundM(double range_m, double body_z_up);

/// Whether `signal` is prepared from the scalar input `scalar` (air density from static pressure
/// and air temperature, height from the rangefinder, a scalar read as it is from itself): the node
/// subscribes to an input only when an effect of its model reads a signal prepared from it. Does
/// not throw.
bool preparedFrom(Signal signal, input::Scalar scalar);

/// Where the readings the effects' signals are prepared from come from: topics by default (MAVROS'
/// names), or what a log's signals were read from.
struct SignalSources {
  std::string battery = kBatteryTopic;    ///< the battery's current
  std::string velocity = kVelocityTopic;  ///< vertical and horizontal speed
  std::string imu = kImuTopic;            ///< attitude
  input::PerScalar<std::string> inputs = input::defaultTopics();  ///< each scalar input's
};

/// "air density on /mavros/imu/static_pressure and /mavros/imu/temperature_baro": the signal's name
/// (signalName) and the sources it is prepared from, joined by "and", for the "needs ..." and
/// "missing or stale" texts; "none" for Signal::kNone. Does not throw.
std::string sourcesOf(Signal signal, const SignalSources& sources);

/// Every signal the effects read, prepared from `raw` with the functions above; the vertical speed
/// and a scalar input read as it is (the motor temperature) as given; the horizontal speed the norm of the velocity's east and
/// north; the axial speed the velocity along the body's z axis (its vertical part alone when the
/// horizontal velocity is missing; NaN without the vertical speed). Does not throw.
Signals prepareSignals(const RawSignals& raw);

}  // namespace effects
}  // namespace propulsion_estimator
