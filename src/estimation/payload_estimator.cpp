#include "propulsion_estimator/estimation/payload_estimator.h"

#include <algorithm>
#include <cmath>

#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/not_a_number.h"

namespace propulsion_estimator {

void PayloadConfig::validate() const {
  requirePositive("payload/averaging_window_s", averaging_window_s);
  if (min_samples < 2) {
    throw FieldError("payload/min_samples", "must be at least 2, got " + std::to_string(min_samples));
  }
  requirePositive("payload/episode_gap_s", episode_gap_s);
}

const char* emptyMassSourceName(EmptyMassSource source) {
  switch (source) {
    case EmptyMassSource::kNone: return "none";
    case EmptyMassSource::kUrdf: return "urdf";
    case EmptyMassSource::kParameter: return "parameter";
    case EmptyMassSource::kTareFile: return "tare_file";
    case EmptyMassSource::kTare: return "tare";
  }
  return "?";
}

const char* payloadStateName(PayloadState state) {
  switch (state) {
    case PayloadState::kWaitingForHover: return "waiting_for_hover";
    case PayloadState::kNoTareYet: return "no_tare_yet";
    case PayloadState::kHovering: return "hovering";
    case PayloadState::kHolding: return "holding";
  }
  return "?";
}

PayloadEstimator::PayloadEstimator(const PayloadConfig& config)
    : config_(config), window_(config.averaging_window_s) {
  updateStatistics();
  clearEmptyMass();
}

const MassEstimate& PayloadEstimator::add(double stamp_s, double mass_kg, bool hovering) {
  if (hovering) {
    if (hovered_before_ && stamp_s - last_hover_stamp_s_ > config_.episode_gap_s) window_.clear();
    window_.add(stamp_s, mass_kg);
    last_hover_stamp_s_ = stamp_s;
    hovered_before_ = true;
    updateStatistics();
  }
  updateState(hovering);
  return estimate_;
}

void PayloadEstimator::setEmptyMass(double mass_kg, EmptyMassSource source) {
  estimate_.empty_mass_kg = mass_kg;
  estimate_.empty_mass_source = source;
  updateState(estimate_.hovering);
}

void PayloadEstimator::clearEmptyMass() { setEmptyMass(kNaN, EmptyMassSource::kNone); }

void PayloadEstimator::clearWindow() {
  window_.clear();
  hovered_before_ = false;
  updateStatistics();
  updateState(false);
}

void PayloadEstimator::endHover() { updateState(false); }

void PayloadEstimator::updateStatistics() {
  MassEstimate& e = estimate_;
  const RunningMoments mass = window_.total();
  e.window_samples = static_cast<std::uint32_t>(mass.count);
  e.window_s = window_.span();
  if (mass.count < config_.min_samples) {
    e.total_mass_kg = e.mass_std_kg = kNaN;
    return;
  }
  e.total_mass_kg = mass.mean;
  e.mass_std_kg = std::sqrt(mass.sampleVariance());
}

void PayloadEstimator::updateState(bool hovering) {
  MassEstimate& e = estimate_;
  e.hovering = hovering;
  e.payload_mass_kg = e.total_mass_kg - e.empty_mass_kg;  // NaN while either is unknown
  e.state = std::isnan(e.total_mass_kg)   ? PayloadState::kWaitingForHover
            : std::isnan(e.empty_mass_kg) ? PayloadState::kNoTareYet
            : hovering                    ? PayloadState::kHovering
                                          : PayloadState::kHolding;
}

}  // namespace propulsion_estimator
