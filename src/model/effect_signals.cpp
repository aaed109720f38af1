#include "propulsion_estimator/model/effect_signals.h"

#include <cmath>

#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace effects {

double airDensityKgM3(double static_pressure_pa, double air_temperature_c) {
  return static_pressure_pa / (kSpecificGasConstantDryAir * (air_temperature_c + kZeroCelsiusInKelvin));
}

double dischargeCurrentA(double reported_a) { return std::fabs(reported_a); }

double heightAboveGroundM(double range_m, double body_z_up) {
  if (!(body_z_up > 0.0)) return kNaN;
  return range_m * body_z_up;
}

namespace {

// The effect signals read as they are from a scalar input, and the input.
struct DirectSignal {
  Signal signal;
  input::Scalar scalar;
};
constexpr DirectSignal kDirectSignals[] = {{Signal::kMotorTemperature, input::Scalar::kMotorTemperature}};

}  // namespace

bool preparedFrom(Signal signal, input::Scalar scalar) {
  using input::Scalar;
  switch (signal) {
    case Signal::kAirDensity: return scalar == Scalar::kStaticPressure || scalar == Scalar::kAirTemperature;
    case Signal::kHeight: return scalar == Scalar::kRangefinder;
    default: break;
  }
  for (const DirectSignal& direct : kDirectSignals) {
    if (direct.signal == signal && direct.scalar == scalar) return true;
  }
  return false;
}

std::string sourcesOf(Signal signal, const SignalSources& sources) {
  std::string topics;
  switch (signal) {
    case Signal::kNone: return "none";
    case Signal::kBatteryCurrent: topics = sources.battery; break;
    case Signal::kVerticalSpeed:
    case Signal::kHorizontalSpeed: topics = sources.velocity; break;
    case Signal::kAxialSpeed: topics = sources.velocity + " and " + sources.imu; break;
    default:
      for (input::Scalar scalar : input::kAllScalars) {
        if (preparedFrom(signal, scalar)) topics += (topics.empty() ? "" : " and ") + sources.inputs[input::index(scalar)];
      }
  }
  return std::string(signalName(signal)) + " on " + topics;
}

Signals prepareSignals(const RawSignals& raw) {
  using input::Scalar;
  Signals signals;
  signals.set(Signal::kBatteryCurrent, dischargeCurrentA(raw.battery_current_a));
  signals.set(Signal::kAirDensity,
              airDensityKgM3(raw.input(Scalar::kStaticPressure), raw.input(Scalar::kAirTemperature)));
  signals.set(Signal::kHeight, heightAboveGroundM(raw.input(Scalar::kRangefinder), raw.body_z_up));
  for (const DirectSignal& direct : kDirectSignals) signals.set(direct.signal, raw.input(direct.scalar));
  signals.set(Signal::kVerticalSpeed, raw.vertical_speed_m_s);
  const double horizontal = std::hypot(raw.velocity_east_m_s, raw.velocity_north_m_s);
  signals.set(Signal::kHorizontalSpeed, horizontal);
  signals.set(Signal::kAxialSpeed,
              raw.vertical_speed_m_s * raw.body_z_up +
                  (std::isfinite(horizontal)
                       ? raw.velocity_east_m_s * raw.body_z_east + raw.velocity_north_m_s * raw.body_z_north
                       : 0.0));
  return signals;
}

}  // namespace effects
}  // namespace propulsion_estimator
