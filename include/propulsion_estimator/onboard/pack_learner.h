#pragma once

#include <array>

#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/onboard/battery_estimator.h"
#include "propulsion_estimator/onboard/ocv_curve.h"
#include "propulsion_estimator/onboard/pack_file.h"

namespace propulsion_estimator {

/// What a flight's readings are taken as: at rest below rest_current_a, resting once that has
/// lasted settle_s.
struct PackLearnerConfig {
  int cells = 0;               ///< in series
  double capacity_ah = 0.0;    ///< Ah; the rated (or last learned) capacity the flight was estimated with
  double rest_current_a = 3.0;  ///< A; below this the pack is at rest (the avionics alone)
  double settle_s = 10.0;       ///< s at rest after landing before its voltage is read as the rest voltage
  /// The least share of the charge between the rest voltages before and after a flight for its
  /// capacity to be learned.
  double min_capacity_span = 0.3;

  /// Throws FieldError (capability/battery/...) for cells outside 1..14, a capacity, current or
  /// time not positive, a span outside 0..1.
  void validate() const;
};

/// Learns a pack from one flight, O(1) per reading in fixed memory: its rest voltage before the
/// take-off and after landing, the charge drawn between (the capacity, read on the curve the flight
/// was estimated with), the voltage it rests at under the hover's load over the charge drawn (the
/// terminal voltage plus the identified resistance times the current, in 48 bins of the charge:
/// the curve as the hover sees it, its slow polarisation included) and the resistance identified
/// (the median over the charge flown: the landing's change of current moves it once more).
class PackLearner {
 public:
  /// Throws FieldError for a bad config.
  explicit PackLearner(PackLearnerConfig config);

  /// One battery reading: s, V, A drawn (its magnitude; NaN: nothing is learned from it), and the
  /// battery estimator's state after it.
  void add(double time_s, double voltage_v, double current_a, const BatteryEstimate& estimate);
  /// Whether a flight has been flown and the pack has rested settle_s since its landing.
  bool flightFinished() const;
  /// s the pack must still rest after a landing before the flight is learned (settle_s less the
  /// rest so far); NaN while no landed flight awaits it.
  double restLeftS() const;
  /// `previous` (the pack's record before this flight, identity and cells set) with this flight
  /// learned, `flown` the curve the flight was estimated with: one more flight, the resistance
  /// appended, the capacity when the rest voltages span min_capacity_span of the charge (averaged
  /// with the one learned before), the curve over the charge flown replacing the record's there.
  PackRecord learned(const PackRecord& previous, const OcvCurve& flown) const;
  /// Forgets the flight: the next one starts from the present rest.
  void startNextFlight();

 private:
  static constexpr int kBins = 48;
  struct Bin {
    double cell_v_sum = 0.0;
    double resistance_sum_ohm = 0.0;
    int count = 0;
  };
  double binWidthAh() const { return 1.2 * config_.capacity_ah / kBins; }

  PackLearnerConfig config_;
  double last_s_ = kNaN;
  double rest_before_v_ = kNaN;  // the last resting voltage before the take-off
  double rest_after_v_ = kNaN;   // the resting voltage after the landing, once settled
  double rest_since_s_ = kNaN;   // when the present rest began
  bool flying_ = false, landed_ = false;
  double drawn_ah_ = 0.0;  // since the take-off
  std::array<Bin, kBins> bins_{};
};

/// The open-circuit curve a pack's record gives, over 0..1: its learned points, and `fallback`
/// (the chemistry's or the user's) beyond them, shifted to meet them so the curve stays continuous
/// and rising. `fallback` itself when the record has fewer than two points or its points give no
/// rising table. Throws nothing.
OcvCurve learnedCurve(const PackRecord& record, const OcvCurve& fallback);

}  // namespace propulsion_estimator
