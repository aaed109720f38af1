#include "propulsion_estimator/onboard/battery_estimator.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "propulsion_estimator/common/cells_in_series.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace {

constexpr double kSecondsPerHour = 3600.0;
// The filter's prior before the first reading: the curve at the voltage read under an unknown load.
constexpr double kInitialSocStd = 0.15;
// Prior spreads of the least squares: the rest voltage within 1 V, the resistance within 50 mOhm.
constexpr double kInitialEStdV = 1.0;
constexpr double kInitialRStdOhm = 0.05;
// A current sensor's bias holds for about this long: the count's variance grows with it.
constexpr double kBiasCorrelationS = 60.0;
// The current's recent mean (s) and the move off it (A) that excites the resistance.
constexpr double kExcitationMeanS = 30.0;
constexpr double kExcitationA = 1.0;
// Below this the resistance's standard deviation counts as identified, however small the resistance.
constexpr double kResistanceStdFloorOhm = 0.003;

}  // namespace

void BatteryEstimatorConfig::validate() const {
  requireWithin("capability/battery/cells", cells, kMinCellsInSeries, kMaxCellsInSeries);
  requirePositive("capability/battery/capacity_ah", capacity_ah, 1000.0, " Ah");
  requirePositive("capability/battery/resistance_memory_s", resistance_memory_s);
  requirePositive("capability/battery/voltage_sigma_v", voltage_sigma_v);
  requireWithin("capability/battery/curve_sigma_cell_v", curve_sigma_cell_v, 0.0, 0.5, " V");
  requireWithin("capability/battery/current_bias_a", current_bias_a, 0.0, 100.0, " A");
  requireWithin("capability/battery/capacity_rel_std", capacity_rel_std, 0.0, 0.5);
  requireWithin("capability/battery/knee_soc_std", knee_soc_std, 0.0, 0.5);
  requireWithin("capability/battery/min_current_span_a", min_current_span_a, 0.0, 1000.0, " A");
  requireWithin("capability/battery/polarisation_rel", polarisation_rel, 0.0, 10.0);
  requirePositive("capability/battery/polarisation_time_s", polarisation_time_s);
  requireWithin("capability/battery/cold_capacity_rel", cold_capacity_rel, 0.0, 0.9);
  requirePositive("capability/battery/interval_low_z", interval_low_z, 10.0);
  requirePositive("capability/battery/interval_high_z", interval_high_z, 10.0);
  requirePositive("capability/battery/max_resistance_rel_std", max_resistance_rel_std);
  requirePositive("capability/battery/max_soc_std", max_soc_std, 1.0);
  if (!std::isnan(initial_resistance_ohm)) {
    requireWithin("capability/battery/pack_file: resistance_ohm", initial_resistance_ohm, 0.0, 10.0, " ohm");
  }
}

BatteryEstimator::BatteryEstimator(BatteryEstimatorConfig config) : config_(std::move(config)) { config_.validate(); }

void BatteryEstimator::add(double time_s, double voltage_v, double current_a) {
  if (!(voltage_v > 0.0) || std::isinf(voltage_v) || std::isnan(time_s)) return;
  const bool have_current = std::isfinite(current_a);
  const double sigma2 = config_.voltage_sigma_v * config_.voltage_sigma_v;
  if (!started_) {
    started_ = true;
    last_s_ = time_s;
    const bool resting = !(current_a >= config_.rest_current_a);
    soc_ = config_.curve.stateOfCharge(voltage_v / config_.cells - (resting ? config_.rest_offset_cell_v : 0.0));
    soc_var_ = kInitialSocStd * kInitialSocStd;
    mean_current_a_ = have_current ? current_a : 0.0;
    const bool known = config_.initial_resistance_ohm > 0.0;
    fit_.reset(Eigen::Vector2d(voltage_v, known ? config_.initial_resistance_ohm : 0.0),
               Eigen::Vector2d(kInitialEStdV, known ? config_.initial_resistance_ohm / 3.0 : kInitialRStdOhm),
               config_.voltage_sigma_v);
  } else {
    if (!(time_s > last_s_)) return;
    const double dt_s = time_s - last_s_;
    last_s_ = time_s;
    if (have_current) {
      countCharge(dt_s, std::isfinite(last_current_a_) ? 0.5 * (current_a + last_current_a_) : current_a);
      updateResistance(dt_s, voltage_v, current_a);
    }
  }
  if (have_current) {
    min_current_a_ = std::isnan(min_current_a_) ? current_a : std::min(min_current_a_, current_a);
    max_current_a_ = std::isnan(max_current_a_) ? current_a : std::max(max_current_a_, current_a);
    if (std::isnan(loaded_since_s_) && max_current_a_ - min_current_a_ >= config_.min_current_span_a) {
      loaded_since_s_ = time_s;
    }
    // The voltage the pack would rest at; its noise, the resistance's spread times the current and
    // how far a pack may lie off the curve.
    const double curve_v = config_.cells * config_.curve_sigma_cell_v;
    const Eigen::Vector2d sag(0.0, current_a);
    // A curve learned under the hover's load lies below the rest by the polarisation a hover
    // builds: a resting voltage is read on it less that.
    const double rest_offset_v = current_a < config_.rest_current_a ? config_.cells * config_.rest_offset_cell_v : 0.0;
    correctWithCurve(voltage_v + sag.dot(fit_.parameters()) - rest_offset_v, sigma2 * (1.0 + sag.dot(fit_.covariance() * sag)) + curve_v * curve_v);
  }
  last_current_a_ = current_a;
  publish();
}

void BatteryEstimator::countCharge(double dt_s, double current_a) {
  const double drawn = current_a * dt_s / (kSecondsPerHour * config_.capacity_ah);
  // The resting voltage the least squares holds follows the curve as the charge is drawn.
  fit_.parameters()(0) -= config_.cells * config_.curve.slope(soc_) * drawn;
  soc_ = std::clamp(soc_ - drawn, 0.0, 1.0);
  const double bias = config_.current_bias_a / (kSecondsPerHour * config_.capacity_ah);
  soc_var_ += bias * bias * dt_s * kBiasCorrelationS;
}

void BatteryEstimator::updateResistance(double dt_s, double voltage_v, double current_a) {
  // V = E - R I: the line's slope against -I is R, which no pack has below zero. Only a change of
  // current tells R from E: while the current stays within kExcitationA of its recent mean (a
  // steady hover) R is held and not forgotten, and the reading moves E alone. Fitting both there
  // let a pack whose curve is not the built-in one (E carried along the wrong slope) pull R to
  // zero, or to five times its value, within ten minutes of hover.
  const bool excited = std::abs(current_a - mean_current_a_) >= kExcitationA;
  const double keep = std::exp(-dt_s / config_.resistance_memory_s);
  fit_.forget(keep, excited ? keep : 1.0);
  if (excited) {
    fit_.add(-current_a, voltage_v);
  } else {
    fit_.addWithSlopeHeld(-current_a, voltage_v);
  }
  fit_.parameters()(1) = std::max(0.0, fit_.parameters()(1));
  mean_current_a_ += std::min(1.0, dt_s / kExcitationMeanS) * (current_a - mean_current_a_);
}

void BatteryEstimator::correctWithCurve(double open_circuit_v, double variance) {
  const double h = config_.cells * config_.curve.cellVoltage(soc_);
  const double slope = config_.cells * config_.curve.slope(soc_);
  const double innovation_var = slope * slope * soc_var_ + variance;
  const double gain = soc_var_ * slope / innovation_var;
  soc_ = std::clamp(soc_ + gain * (open_circuit_v - h), 0.0, 1.0);
  soc_var_ *= 1.0 - gain * slope;
}

void BatteryEstimator::addStateOfCharge(double state_of_charge, double sigma) {
  if (!started_ || !(state_of_charge >= 0.0 && state_of_charge <= 1.0) || !(sigma > 0.0)) return;
  const double gain = soc_var_ / (soc_var_ + sigma * sigma);
  soc_ += gain * (state_of_charge - soc_);
  soc_var_ *= 1.0 - gain;
  publish();
}

void BatteryEstimator::publish() {
  const double sigma2 = config_.voltage_sigma_v * config_.voltage_sigma_v;
  // The curve's own uncertainty is a bias, not averaged away: the spread never falls below it.
  const double curve_soc = config_.curve_sigma_cell_v / config_.curve.slope(soc_);
  estimate_.state_of_charge = soc_;
  estimate_.state_of_charge_std = std::sqrt(soc_var_ + curve_soc * curve_soc);
  estimate_.internal_resistance_ohm = fit_.parameters()(1);
  estimate_.internal_resistance_std_ohm = std::sqrt(std::max(0.0, fit_.covariance()(1, 1) * sigma2));
  estimate_.open_circuit_voltage_v = fit_.parameters()(0);
  estimate_.current_a = last_current_a_;
  estimate_.current_span_a = std::isnan(max_current_a_) ? 0.0 : max_current_a_ - min_current_a_;
  estimate_.loaded_s = std::isnan(loaded_since_s_) ? 0.0 : last_s_ - loaded_since_s_;
}

std::string BatteryEstimator::withheldReason() const {
  if (!started_) return "no battery voltage yet";
  const BatteryEstimate& b = estimate_;
  if (std::isnan(b.current_a) && b.current_span_a == 0.0) return "no battery current (measured or modelled) yet";
  if (b.current_span_a < config_.min_current_span_a) {
    return "internal resistance not identified yet: the current has varied by " + formatPrintf("%.1f A", b.current_span_a) +
           ", " + formatPrintf("%.1f A", config_.min_current_span_a) + " needed (a take-off gives it)";
  }
  if (b.internal_resistance_std_ohm >
      std::max(config_.max_resistance_rel_std * b.internal_resistance_ohm, kResistanceStdFloorOhm)) {
    return "internal resistance converging: " + formatPrintf("%.1f", 1000.0 * b.internal_resistance_ohm) + " +- " +
           formatPrintf("%.1f mOhm", 1000.0 * b.internal_resistance_std_ohm);
  }
  if (b.state_of_charge_std > config_.max_soc_std) {
    return "state of charge converging: " + formatPrintf("%.0f", 100.0 * b.state_of_charge) + " +- " +
           formatPrintf("%.0f %%", 100.0 * b.state_of_charge_std);
  }
  return "";
}

}  // namespace propulsion_estimator
