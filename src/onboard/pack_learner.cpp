#include "propulsion_estimator/onboard/pack_learner.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "propulsion_estimator/common/cells_in_series.h"
#include "propulsion_estimator/common/field_error.h"

namespace propulsion_estimator {
namespace {

constexpr double kSecondsPerHour = 3600.0;
// The curve's points of a flight: bins with fewer readings are noise.
constexpr int kMinBinReadings = 5;
// Learned points closer than this in charge are one.
constexpr double kMinSocStep = 1e-3;
// Below and above the learned points the fallback keeps its shape, and rises at least this.
constexpr double kMinRiseV = 1e-4;

}  // namespace

void PackLearnerConfig::validate() const {
  requireWithin("capability/battery/cells", cells, kMinCellsInSeries, kMaxCellsInSeries);
  requirePositive("capability/battery/capacity_ah", capacity_ah, 1000.0, " Ah");
  requirePositive("capability/battery/rest_current_a", rest_current_a, 1000.0, " A");
  requirePositive("capability/battery/settle_s", settle_s);
  requireWithin("capability/battery/min_capacity_span", min_capacity_span, 0.0, 1.0);
}

PackLearner::PackLearner(PackLearnerConfig config) : config_(std::move(config)) { config_.validate(); }

void PackLearner::add(double time_s, double voltage_v, double current_a, const BatteryEstimate& estimate) {
  if (!(voltage_v > 0.0) || std::isinf(voltage_v) || !std::isfinite(current_a) || !std::isfinite(time_s)) return;
  if (!std::isnan(last_s_) && !(time_s > last_s_)) return;
  const double dt_s = std::isnan(last_s_) ? 0.0 : time_s - last_s_;
  last_s_ = time_s;
  const bool at_rest = current_a < config_.rest_current_a;
  if (at_rest) {
    if (std::isnan(rest_since_s_)) rest_since_s_ = time_s;
    if (!flying_) rest_before_v_ = voltage_v;
    if (flying_ && time_s - rest_since_s_ >= config_.settle_s) {
      landed_ = true;
      rest_after_v_ = voltage_v;
    }
  } else {
    rest_since_s_ = kNaN;
    flying_ = flying_ || !std::isnan(rest_before_v_);
  }
  if (!flying_ || landed_) return;
  drawn_ah_ += current_a * dt_s / kSecondsPerHour;
  if (at_rest || !std::isfinite(estimate.internal_resistance_ohm) || estimate.current_span_a < config_.rest_current_a) {
    return;
  }
  const int bin = static_cast<int>(drawn_ah_ / binWidthAh());
  if (bin < 0 || bin >= kBins) return;
  bins_[bin].cell_v_sum += (voltage_v + estimate.internal_resistance_ohm * current_a) / config_.cells;
  bins_[bin].resistance_sum_ohm += estimate.internal_resistance_ohm;
  ++bins_[bin].count;
}

bool PackLearner::flightFinished() const { return landed_; }

double PackLearner::restLeftS() const {
  if (!flying_ || landed_ || std::isnan(rest_since_s_)) return kNaN;
  return std::max(0.0, config_.settle_s - (last_s_ - rest_since_s_));
}

PackRecord PackLearner::learned(const PackRecord& previous, const OcvCurve& flown) const {
  PackRecord record = previous;
  if (!landed_) return record;
  ++record.flights;
  std::vector<double> resistances;
  for (const Bin& bin : bins_) {
    if (bin.count >= kMinBinReadings) resistances.push_back(bin.resistance_sum_ohm / bin.count);
  }
  if (!resistances.empty()) {
    std::nth_element(resistances.begin(), resistances.begin() + resistances.size() / 2, resistances.end());
    record.resistance_ohm.push_back(resistances[resistances.size() / 2]);
  }
  const double soc_start = flown.stateOfCharge(rest_before_v_ / config_.cells);
  const double soc_end = flown.stateOfCharge(rest_after_v_ / config_.cells);
  double capacity = previous.capacity_ah.value_or(config_.capacity_ah);
  if (soc_start - soc_end >= config_.min_capacity_span && drawn_ah_ > 0.0) {
    const double flight_capacity = drawn_ah_ / (soc_start - soc_end);
    capacity = previous.capacity_ah ? 0.5 * (*previous.capacity_ah + flight_capacity) : flight_capacity;
    record.capacity_ah = capacity;
  }
  // This flight's points, by charge left, rising; where the voltage does not rise (noise on a flat
  // stretch) the later point is left out.
  std::vector<std::pair<double, double>> flight;
  for (int k = kBins - 1; k >= 0; --k) {
    if (bins_[k].count < kMinBinReadings) continue;
    const double soc = soc_start - (k + 0.5) * binWidthAh() / capacity;
    const double cell_v = bins_[k].cell_v_sum / bins_[k].count;
    if (soc < 0.0 || soc > 1.0) continue;
    if (!flight.empty() && (soc - flight.back().first < kMinSocStep || cell_v <= flight.back().second)) continue;
    flight.emplace_back(soc, cell_v);
  }
  if (flight.size() < 2) return record;
  // The last loaded point against the rest after the landing: how far the hover's polarisation
  // holds the loaded curve below the rest.
  const double offset = rest_after_v_ / config_.cells - flight.front().second;
  record.rest_offset_cell_v =
      previous.rest_offset_cell_v ? 0.5 * (*previous.rest_offset_cell_v + offset) : offset;
  // The record's points outside the charge flown stay, where they keep the curve rising.
  std::vector<std::pair<double, double>> merged;
  for (std::size_t k = 0; k < previous.ocv_soc.size(); ++k) {
    const double soc = previous.ocv_soc[k];
    if (soc < flight.front().first - kMinSocStep) merged.emplace_back(soc, previous.ocv_cell_v[k]);
  }
  while (!merged.empty() && merged.back().second >= flight.front().second) merged.pop_back();
  merged.insert(merged.end(), flight.begin(), flight.end());
  for (std::size_t k = 0; k < previous.ocv_soc.size(); ++k) {
    const double soc = previous.ocv_soc[k];
    if (soc > flight.back().first + kMinSocStep && previous.ocv_cell_v[k] > merged.back().second) {
      merged.emplace_back(soc, previous.ocv_cell_v[k]);
    }
  }
  record.ocv_soc.clear();
  record.ocv_cell_v.clear();
  for (const auto& [soc, cell_v] : merged) {
    record.ocv_soc.push_back(soc);
    record.ocv_cell_v.push_back(cell_v);
  }
  return record;
}

void PackLearner::startNextFlight() {
  const PackLearnerConfig config = config_;
  const double rest_v = rest_after_v_, rest_since = rest_since_s_, last = last_s_;
  *this = PackLearner(config);
  rest_before_v_ = rest_v;
  rest_since_s_ = rest_since;
  last_s_ = last;
}

OcvCurve learnedCurve(const PackRecord& record, const OcvCurve& fallback) {
  if (record.ocv_soc.size() < 2) return fallback;
  const double lo_soc = record.ocv_soc.front(), hi_soc = record.ocv_soc.back();
  const double below_shift = record.ocv_cell_v.front() - fallback.cellVoltage(lo_soc);
  const double above_shift = record.ocv_cell_v.back() - fallback.cellVoltage(hi_soc);
  std::vector<double> soc, cell_v;
  const auto push = [&](double s, double v) {
    if (!soc.empty() && (s - soc.back() < kMinSocStep || v < cell_v.back() + kMinRiseV)) return;
    soc.push_back(s);
    cell_v.push_back(v);
  };
  for (std::size_t k = 0; k < fallback.socTable().size(); ++k) {
    const double s = fallback.socTable()[k];
    if (s < lo_soc) push(s, std::max(2.0, fallback.cellVTable()[k] + below_shift));
  }
  for (std::size_t k = 0; k < record.ocv_soc.size(); ++k) push(record.ocv_soc[k], record.ocv_cell_v[k]);
  for (std::size_t k = 0; k < fallback.socTable().size(); ++k) {
    const double s = fallback.socTable()[k];
    if (s > hi_soc) push(s, std::min(4.5, fallback.cellVTable()[k] + above_shift));
  }
  // The table runs from 0 to 1: its ends where the learned points reach them.
  if (soc.front() > 0.0 && cell_v.front() - kMinRiseV < 2.0) soc.front() = 0.0;
  if (soc.front() > 0.0) {
    soc.insert(soc.begin(), 0.0);
    cell_v.insert(cell_v.begin(), cell_v.front() - kMinRiseV);
  }
  if (soc.back() < 1.0 && cell_v.back() + kMinRiseV > 4.5) soc.back() = 1.0;
  if (soc.back() < 1.0) {
    soc.push_back(1.0);
    cell_v.push_back(cell_v.back() + kMinRiseV);
  }
  if (soc.size() < 2) return fallback;
  try {
    return OcvCurve(soc, cell_v, "capability/battery/pack_file");
  } catch (const FieldError&) {
    // Points a reader accepted that still give no rising table (closer than the steps above):
    // nothing to learn from them.
    return fallback;
  }
}

}  // namespace propulsion_estimator
