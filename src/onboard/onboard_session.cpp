#include "propulsion_estimator/onboard/onboard_session.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/model/effect_signals.h"

namespace propulsion_estimator {

OnboardSession::OnboardSession(PropulsionModel model, Vehicle vehicle, const OnboardConfig& config,
                               const std::string& model_name)
    : config_(config),
      estimator_(std::move(model), std::move(vehicle), config.estimator),
      capability_(estimator_.model(), static_cast<int>(estimator_.vehicle().rotors.size()), config.capability),
      motor_health_(estimator_.vehicle(), config.estimator.motor_channels, config.capability.motor_health,
                    estimator_.model().motorReference()),
      model_check_(config.estimator.motor_channels, config.esc_telemetry) {
  const PropulsionModel& m = estimator_.model();
  if (const auto& reference = m.motorReference(); reference && !reference->esc_rpm_deviation.empty()) {
    model_check_.setBaseline(reference->esc_rpm_deviation, reference->esc_current_deviation, reference->esc_rpm_level);
  }
  if (m.rpmThrust()) rpm_view_.emplace(*m.rpmThrust(), config.estimator.payload.averaging_window_s);
  if (config.mass_view == "rpm" && !m.rpmThrust()) {
    throw ConfigError("esc_telemetry/mass_view: rpm, but " + model_name +
                      " has no thrust_from_rpm (fit_surfaces writes it from bench logs with an rpm column)");
  }
  battery_current_ = config.esc_telemetry.apply_supply_resistance || reads(effects::Signal::kBatteryCurrent);
  for (input::Scalar scalar : input::kAllScalars) {
    inputs_read_[input::index(scalar)] =
        scalar == input::Scalar::kStaticPressure ||
        std::any_of(effects::allSignals().begin(), effects::allSignals().end(),
                    [&](effects::Signal signal) { return reads(signal) && effects::preparedFrom(signal, scalar); });
  }
}

bool OnboardSession::reads(effects::Signal signal) const {
  const effects::ModelEffects& fx = estimator_.model().effects();
  return std::any_of(effects::kAllKinds.begin(), effects::kAllKinds.end(),
                     [&](effects::Kind kind) { return fx.has(kind) && effects::requiredSignal(kind) == signal; });
}

Rejection OnboardSession::addMotorOutputs(double stamp_s, double now_s, const std::uint16_t* channels,
                                          std::size_t count) {
  const Rejection verdict = estimator_.addMotorOutputs(stamp_s, now_s, channels, count);
  if (verdict != Rejection::kNone) return verdict;
  const EstimatorOutput& output = estimator_.output();
  motor_health_.add(output);
  model_check_.addEstimate(now_s, output);
  // The air density is prepared only for a hover, the one sample the view takes.
  if (rpm_view_) {
    rpm_view_->add(now_s, output, model_check_,
                   output.hover.hovering ? estimator_.effectSignals(now_s).value(effects::Signal::kAirDensity) : kNaN);
  }
  return verdict;
}

Rejection OnboardSession::addBattery(double now_s, double voltage_v, double current_a, double percentage,
                                     double temperature_c) {
  Rejection verdict = estimator_.addBattery(now_s, voltage_v);
  if (battery_current_) {
    const Rejection current = estimator_.addBatteryCurrent(now_s, current_a);
    if (verdict == Rejection::kNone) verdict = current;
  }
  model_check_.addBattery(now_s, voltage_v);
  applySupplyResistance();
  // The modelled current stands in for a current the autopilot does not measure (NaN).
  const double modelled_a = estimator_.model().output(Output::kCurrent).source == OutputSource::kNone
                                ? kNaN
                                : estimator_.output().totals.current_a;
  capability_.addBattery(now_s, voltage_v, BatteryReport{percentage, current_a, temperature_c}, modelled_a);
  return verdict;
}

Rejection OnboardSession::addImu(double now_s, const Eigen::Quaterniond& orientation,
                                 const Eigen::Vector3d& specific_force) {
  return estimator_.addImu(now_s, orientation, specific_force);
}

Rejection OnboardSession::addVerticalSpeed(double now_s, double vertical_speed_m_s) {
  return estimator_.addVerticalSpeed(now_s, vertical_speed_m_s);
}

Rejection OnboardSession::addHorizontalVelocity(double now_s, double east_m_s, double north_m_s) {
  return estimator_.addHorizontalVelocity(now_s, east_m_s, north_m_s);
}

Rejection OnboardSession::addInput(input::Scalar scalar, double now_s, double value) {
  return readsInput(scalar) ? estimator_.addInput(scalar, now_s, value) : Rejection::kNone;
}

Rejection OnboardSession::addRange(double now_s, double range_m, double min_range_m, double max_range_m) {
  return readsInput(input::Scalar::kRangefinder) ? estimator_.addRange(now_s, range_m, min_range_m, max_range_m)
                                                 : Rejection::kNone;
}

void OnboardSession::addEscTelemetry(double now_s, const EscTelemetry& message) {
  model_check_.addTelemetry(now_s, message);
}

void OnboardSession::applySupplyResistance() {
  if (!config_.esc_telemetry.apply_supply_resistance) return;
  const double ohm = model_check_.supplyResistanceOhm();
  if (std::isnan(ohm)) return;
  // A new model only when the estimate has moved by more than its own resolution (1 mOhm or 5 %).
  if (!std::isnan(supply_applied_ohm_) &&
      std::fabs(ohm - supply_applied_ohm_) < std::max(0.001, 0.05 * supply_applied_ohm_)) {
    return;
  }
  estimator_.setEffect(effects::Kind::kSupplyResistance, ohm);
  supply_applied_ohm_ = ohm;
}

bool OnboardSession::rpmViewInUse(double now_s) const {
  if (config_.mass_view != "rpm" || !rpm_view_ || std::isnan(rpm_view_->massKg())) return false;
  for (std::size_t k = 0; k < config_.estimator.motor_channels.size(); ++k) {
    if (std::isnan(model_check_.motor(k, now_s).measured_rpm)) return false;
  }
  return true;
}

CapabilityState OnboardSession::capability(double now_s) {
  estimator_.expireHover(now_s);
  CapabilityState state;
  state.rpm_mass_view = rpmViewInUse(now_s);
  const EstimatorOutput* input = &estimator_.output();
  if (state.rpm_mass_view) {
    rpm_output_ = estimator_.output();
    rpm_output_.payload.total_mass_kg = rpm_view_->massKg();
    rpm_output_.payload.window_s = rpm_view_->hoverS();
    input = &rpm_output_;
  }
  state.capability = capability_.evaluate(*input, estimator_.effectSignals(now_s));
  state.motor_health = motor_health_.verdict();
  state.model_check = model_check_.report(now_s);
  state.rpm_view_mass_kg = rpm_view_ ? rpm_view_->massKg() : kNaN;
  state.supply_applied_ohm = supply_applied_ohm_;
  return state;
}

HealthStatus OnboardSession::payloadHealth(double now_s) {
  estimator_.expireHover(now_s);
  return judgePayload(estimator_);
}

std::pair<bool, std::string> OnboardSession::detectHover(double now_s) {
  estimator_.expireHover(now_s);
  const EstimatorOutput& out = estimator_.output();
  std::ostringstream message;
  message.precision(4);
  message << estimator_.describeHover();
  if (!std::isnan(out.payload.total_mass_kg)) {
    message << "; averaged mass " << out.payload.total_mass_kg << " kg (std " << out.payload.mass_std_kg << " kg, "
            << out.payload.window_samples << " samples over " << out.payload.window_s << " s)";
  }
  return {out.hover.hovering, message.str()};
}

void OnboardSession::reset() {
  estimator_.reset();
  motor_health_.clear();
  model_check_.reset();
  if (rpm_view_) rpm_view_->reset();
}

}  // namespace propulsion_estimator
