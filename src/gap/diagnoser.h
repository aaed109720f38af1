// The gap diagnosis' steps (private to src/gap/): diagnosis.cpp holds the cut into blocks and the
// selection of effects, diagnosis_report.cpp what the diagnosis reports of them,
// reference_effects.cpp the effects of a vehicle's healthy flights.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "propulsion_estimator/gap/diagnosis.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/gap/blocks.h"
#include "propulsion_estimator/gap/effect_fit.h"
#include "propulsion_estimator/gap/motor_balance.h"
#include "propulsion_estimator/gap/parts_spread.h"
#include "propulsion_estimator/gap/rotor_lag.h"
#include "propulsion_estimator/gap/sign_flip_test.h"
#include "propulsion_estimator/gap/thrust_views.h"
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {


using effects::Kind;

// A, the most the avionics (flight controller, companion computer, radios, camera) draw beside the
// motors: the current view's nuisance is sought within 0..this.
constexpr double kMaxAvionicsCurrentA = 3.0;
// |bias| of a flight beyond which the gap is no unmodelled effect but a mass in other units, a
// segment on the ground or another vehicle's model, %.
constexpr double kImplausibleBiasPct = 50.0;
// What the cut into blocks left out, for the one line that says why nothing could be used.
struct UnusedData {
  int transient = 0;               // blocks changing or accelerating beyond the steadiness bounds
  int without_attitude = 0;        // blocks with a frame lacking the attitude
  int frames_without_battery = 0;  // rc/out frames without a fresh battery voltage
  int rejected_outside = 0;        // blocks outside the domain of a model whose policy is reject
};
// How the diagnosis and the healthy reference alike cut flights into blocks for `model`.
BlockConfig blockConfig(const DiagnosisConfig& config, const PropulsionModel& model, int motors,
                        double rotor_time_constant_s);
// The report's clause on the current the avionics draw beside the motors: measured on the flights
// named in `measured` ("0.61 A on f1.bag"), fitted on those in `unmeasured` (diagnosis_report.cpp).
std::string groundDrawText(const std::vector<std::string>& measured, const std::vector<std::string>& unmeasured,
                           double stopped_pwm_us);
// "no usable sample in any weighed segment of any flight: ..." with each reason's count and
// bound, or, when no block was cut at all, why each segment was skipped (FlightBlocks::skipped;
// usable_data.cpp).
std::string nothingUsable(const UnusedData& unused, const DiagnosisConfig& config,
                          const std::vector<std::string>& skipped);
// A line when most blocks lie outside the model's domain, naming the flights' ranges beside the
// model's: is this the right model? nullopt otherwise (usable_data.cpp).
std::optional<std::string> outsideTheDomain(const std::vector<Block>& blocks, const ModelDomain& domain, int motors);

// A signal changes "mostly between flights" when more than this share of its variance over the
// blocks lies between the flights' means (betweenFlightShare): a majority, not a calibration.
constexpr double kMostlyBetweenFlights = 0.5;

// Passes of revisitRounds at most: each pass stops at the first round that changed.
constexpr int kMaxRevisitPasses = 6;
// At most this many of the vehicle's own effects are modelled as the background (not named).
constexpr int kMaxBackgroundEffects = 2;

// What one round of the selection chose: its leader and, when the flights cannot tell it from
// other candidates, the group.
struct RoundOutcome {
  Kind leader;
  std::optional<Ambiguity> ambiguity;
  int round = 0;  // 0-based, its place in the forward selection
};

// The median of `signal` over the blocks that read it; NaN for Signal::kNone or none read.
inline double signalMedian(const std::vector<const Block*>& blocks, effects::Signal signal) {
  if (signal == effects::Signal::kNone) return kNaN;
  std::vector<double> values;
  for (const Block* block : blocks) {
    const double value = block->signals.value(signal);
    if (std::isfinite(value)) values.push_back(value);
  }
  if (values.empty()) return kNaN;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// Mean of the finite squares of `view` (per block; the PWM view's are all finite); NaN when none
// is finite (no such view).
inline double finiteMeanSquare(const std::vector<double>& view) {
  double sum = 0.0;
  int count = 0;
  for (double r : view) {
    if (!std::isfinite(r)) continue;
    sum += r * r;
    ++count;
  }
  return count > 0 ? sum / count : kNaN;
}

// Held-out predictions of one set of effects: each block's relative residual in both views,
// from the fit on the folds that left its flight (or segment) out.
struct HeldOutPrediction {
  std::vector<double> pwm;      // per block
  std::vector<double> current;  // NaN where the current view is unavailable
  std::vector<double> rpm;      // NaN where the RPM view is unavailable
  std::vector<double> view_n;   // PWM view, N
};

// A candidate a round refused only as the vehicle's own, and its held-out prediction on top of the
// round's effects.
struct OwnCandidate {
  Kind kind;
  HeldOutPrediction prediction;
};

// Effects fitted with their strength free to differ between light and heavy loads (by the load
// that explains most): what a later round's effect must beat (law_left_over.cpp).
struct FlexibleLaw {
  HeldOutPrediction prediction;
  double mean_square = 0.0;  // joint, over the blocks
  std::string load;          // "current", "collective command", ...
};


class Diagnoser {
 public:
  Diagnoser(const PropulsionModel& model, const Vehicle& vehicle, const std::vector<Flight>& flights,
            const DiagnosisConfig& config, const std::vector<BenchLog>& bench)
      : model_(model), vehicle_(vehicle), flights_(flights), bench_(bench), config_(config),
        views_(model, motorCount(), config.rpm_view) {}

  Diagnosis run();
  // Each effect fitted on these flights (a vehicle's healthy ones, with their own levels from
  // config.motor_reference) on top of the day's air, and the range of the signal it reads
  // (fitReferenceEffects).
  ReferenceEffects fitEachBesideTheAir();

 private:
  // Each of `kinds_to_fit` that these blocks can test, fitted on them beside the day's air.
  ReferenceEffects fitEach(const std::vector<Kind>& kinds_to_fit) const;
  // The 95 % half-width of the last of `kinds`' parameters, fitted with the others, from each
  // flight left out in turn; 0 with fewer than three flights (reference_effects.cpp).
  double jackknifeHalfWidth(const std::vector<Kind>& kinds) const;
  // `fit_half`, or for an effect read mostly between flights and compared with the healthy
  // flights' the larger of it and its jackknife over these flights (kinds.back() with the others).
  double flightsHalfWidth(const std::vector<Kind>& kinds, double fit_half) const;
  // The share of `signal`'s variance over the blocks between the flights' means (NaN without it).
  double betweenFlightShare(effects::Signal signal) const;
  // Whether `kind`'s signal changes mostly between flights (the day's air): its share above
  // kMostlyBetweenFlights; false for an effect reading none.
  bool readBetweenFlights(Kind kind) const {
    return betweenFlightShare(effects::requiredSignal(kind)) > kMostlyBetweenFlights;
  }

  // A diagnosis of the outer one's blocks kept only (`keep_block`, per block), seeing them through
  // `views`: fresh ones for the nested hold-out, the outer's (with its suspect's factor) for the
  // selection on steady blocks.
  Diagnoser(const Diagnoser& outer, const std::vector<bool>& keep_block, const ThrustViews& views);
  // The suspect motor, the selection and the fit, on this diagnoser's blocks only: the effects the
  // correction uses (selected and ambiguous leaders), fitted; views_ carries the suspect's factor.
  effects::ModelEffects selectAndFit();
  void nestedHoldOut();
  // The selection (selectEffects), on the blocks selectionMask() keeps; then the held-out
  // prediction of what it chose on every block.
  HeldOutPrediction select(const HeldOutPrediction& before, std::map<Kind, EffectResult>* results);
  // The blocks the selection runs on: the steady ones inside the model's domain, else the steady
  // ones, whichever first leaves out some and keeps enough stretches for the test; empty: all.
  std::vector<bool> selectionMask() const;
  // The sign-flip test's units (flight, group) among the blocks `mask` keeps (empty: all).
  int stretchCount(const std::vector<bool>& mask) const;
  // Whether the flights tell `leader` from the other candidates that passed every test in its
  // round (`admissible`, their held-out predictions): the group it cannot be told from, or nullopt.
  std::optional<Ambiguity> ambiguityOf(Kind leader, const std::map<Kind, HeldOutPrediction>& admissible);
  // Each candidate's one line once the selection is over: taken, ambiguous, or why not.
  void finishReasons(std::map<Kind, EffectResult>* results) const;
  int motorCount() const { return static_cast<int>(vehicle_.rotors.size()); }
  // The fewest blocks an effect acting on some blocks only needs there to be tested: the larger
  // of 4 and a fiftieth of the blocks.
  int minInformativeBlocks() const { return std::max(4, static_cast<int>(blocks_.size()) / 50); }
  // Whether the motor balance found a suspect (its factor then rides on views_).
  bool hasSuspect() const { return diagnosis_.motors.suspect_channel.has_value(); }
  double rotorLag();
  void cut();
  void findUnits();
  // What the effects are read against: the bench, or the reference flights' air and warmth.
  effects::ModelEffects references() const;
  std::string testability(Kind kind) const;
  HeldOutPrediction predictHeldOut(const std::vector<Kind>& kinds) const;
  // `kinds` fitted apart on the light and the heavy half (by `load`) of each unit's training blocks.
  using LoadOf = std::function<double(const Block&)>;
  HeldOutPrediction predictHeldOutByLoad(const std::vector<Kind>& kinds, const LoadOf& load) const;
  // The effects each held-out block is seen through, from one fit on the other units' blocks.
  using EffectsOfBlock = std::function<const effects::ModelEffects&(const Block&)>;
  using UnitFit = std::function<EffectsOfBlock(const std::vector<const Block*>& training)>;
  HeldOutPrediction predictHeldOutWith(const UnitFit& fit_unit) const;
  // `kinds` with their strength free to differ between light and heavy loads, by the load that
  // explains most (law_left_over.cpp).
  const FlexibleLaw& flexibleLaw(const std::vector<Kind>& kinds);
  // Why `kind`, read from a signal that changes mostly between flights within the healthy flights'
  // range, cannot be told in a later round from an earlier effect's leftover; "" otherwise.
  std::string readBetweenFlightsAsBefore(Kind kind) const;
  // After the earlier rounds' effects (`earlier`) and a suspect's or lacking rotor's factor
  // (lackingMotorLaw; either may be none):
  // "" when candidate `kind` (of `size`, `regional` where its law acts, held-out prediction `with`
  // of joint mean square `ms`) is more than what their laws leave over (law_left_over.cpp); else
  // why not.
  std::string leftOverOfLaw(Kind kind, const std::vector<Kind>& earlier, const EffectSize& size,
                            const RegionalError& regional, const HeldOutPrediction& with, double ms);
  // Why `kind` is not named on top of `selected`: the motor the balance shows lacking most beyond
  // three standard errors explains it (lacking_motor.cpp); "" otherwise, with a suspect's factor
  // applied or no such motor.
  std::string oneLackingMotorExplains(Kind kind, const std::vector<Kind>& selected) const;
  // The motor the balance shows lacking most beyond three standard errors, no suspect's factor
  // applied; -1 when none.
  int lackingMotor() const;
  // This diagnosis with motor `lacking`'s factor applied, fitted to the weighed thrust within
  // twice the balance's gap (suspectThrustFactor).
  Diagnoser withLackingMotor(int lacking) const;
  // "channel N's factor (...)" when the lacking motor's factor alone lowers the held-out error as
  // a name needs (an earlier law for leftOverOfLaw); "" otherwise.
  std::string lackingMotorLaw();
  // A view's weight in the joint error: the PWM view's block-to-block noise variance over the
  // view's (`view`, from the plain model's held-out residuals `before`); 1 without the view.
  double viewWeight(const HeldOutPrediction& before, const std::vector<double>& view) const;
  // One block's joint squared error: the PWM view's plus the weighted current and RPM views' where
  // they exist.
  double jointSquare(const HeldOutPrediction& prediction, std::size_t block) const;
  // Per (flight, group) stretch: the fall of the joint squared error from `before` to `after`.
  std::vector<double> groupImprovements(const HeldOutPrediction& before, const HeldOutPrediction& after) const;
  // Whether a view's held-out RMSE (% of the truth) falls from `before_pct` to `after_pct` by more
  // than min_improvement_pct points and below max_mean_square_ratio of its mean square; false
  // when either is NaN (no such view).
  bool fallsEnough(double before_pct, double after_pct) const { return fallsBy(before_pct, after_pct, config_.min_improvement_pct); }
  // The same against `min_points` (min_improvement_pct, or a min_regional_improvement_pct where a
  // law acts on some blocks only).
  bool fallsBy(double before_pct, double after_pct, double min_points) const;
  // `kind`'s held-out error before (`base`) and with it (`with`) on the blocks its law acts on
  // (where_it_acts.cpp).
  RegionalError regionalError(Kind kind, const HeldOutPrediction& base, const HeldOutPrediction& with) const;
  // Whether `block` is one the effect of `description` says its law acts on (its informative
  // blocks, its signal present); false for an effect acting on every block (where_it_acts.cpp).
  bool actsOn(const effects::EffectDescription& description, const Block& block) const;
  // Whether `kind`'s regional error falls in either view by more than its entry in `thresholds`
  // (min_regional_improvement_pct, or min_later_regional_improvement_pct); false without one
  // (where_it_acts.cpp).
  bool fallsWhereItActs(Kind kind, const RegionalError& regional, const std::map<Kind, double>& thresholds) const;
  // ", nor on the 96 blocks where its law acts (PWM view ...; > 0.140 points needed there)", the
  // numbers of fallsWhereItActs' test against `thresholds`; "" for an effect without an entry.
  std::string regionalClause(Kind kind, const RegionalError& regional, const std::map<Kind, double>& thresholds) const;
  // "; nor does its held-out error on the 96 blocks where its law acts fall by more than what an
  // earlier law leaves there (...; > 0.365 points needed)": a later round's refusal by size, its
  // regional test against `thresholds` added; "" for an effect without an entry.
  std::string laterRegionalClause(Kind kind, const RegionalError& regional,
                                  const std::map<Kind, double>& thresholds) const;
  // Mean over blocks of the joint squared error.
  double jointMeanSquare(const HeldOutPrediction& prediction) const;
  // The joint mean square once each flight's mean residual is taken out of each view.
  double withinFlightMeanSquare(const HeldOutPrediction& prediction) const;
  double suspectThrustFactor(int motor, double yaw_gap) const;
  double currentViewRatio(const effects::ModelEffects& without, const effects::ModelEffects& with) const;
  double meanPwm(const Block& block) const;
  void addProblemOnce(const std::string& problem);
  std::string standoutMotor() const;

  // The steps of run(), in order.
  void reportGap(const BlockView& pwm_view, const std::vector<double>& plain_view);
  void reportWhere(const BlockView& pwm_view);
  Breakdown operatingRegion(const BlockView& pwm_view) const;
  Breakdown phase(const BlockView& pwm_view) const;
  void balanceMotors();
  HeldOutPrediction selectEffects(const HeldOutPrediction& before, std::map<Kind, EffectResult>* results);
  // Why `kind` fitted with `kinds` is the vehicle's own (within the parts' spread, no change from
  // the healthy flights), or "".
  std::string vehiclesOwn(Kind kind, const std::vector<Kind>& kinds, const EffectFit& fit, const EffectSize& size) const;
  // Whether `candidate`, fitted on top of the vehicle's own `own`, is the vehicle's own as well.
  bool ownOnTopOf(Kind own, Kind candidate) const;
  // Whether `candidate` still improves enough once the vehicle's own (`own`, its prediction with
  // the rounds' effects) is modelled beside the rounds' effects.
  bool passesOnTopOf(const OwnCandidate& own, Kind candidate) const;
  // `candidate`'s verdict, in the results and in the trace's steps from `first_step` on: passed, but
  // what it explains is the vehicle's own `own`'s.
  void declineForTheVehiclesOwn(Kind candidate, Kind own, std::size_t first_step,
                                std::map<Kind, EffectResult>* results);
  // Whether a candidate predicting `with_candidate` leaves less of the error within flights than
  // the vehicle's own `own` would.
  bool explainsMoreWithinFlights(const HeldOutPrediction& with_candidate, const OwnCandidate& own) const;
  // `current` with `own` modelled unnamed beside the rounds' effects, where that lowers the error.
  HeldOutPrediction offerToTheCorrection(Kind own, const std::vector<RoundOutcome>& rounds,
                                         const HeldOutPrediction& current);
  // Prefixes the trace's steps from `first_step` on with the background they ran on top of.
  void markOnBackground(std::size_t first_step);
  // working_, grouped_ and the diagnosis' selected and ambiguous lists from the rounds' outcomes.
  void adopt(const std::vector<RoundOutcome>& rounds);
  // Each round chosen again with the other rounds' effects in, until nothing changes; the held-out
  // prediction of what remains.
  HeldOutPrediction revisitRounds(std::vector<RoundOutcome>* rounds, std::map<Kind, EffectResult>* results);
  // One round of the forward selection: every candidate tried on top of `selected`; the best one
  // that passes every test, or nullopt.
  // `own`, when given: the best candidate that passed the tests of improvement and was refused only
  // as the vehicle's own (within the parts' spread, or no change from its healthy flights), with
  // its held-out prediction on top of `selected`.
  std::optional<Kind> selectionRound(int round, const std::vector<Kind>& selected, const HeldOutPrediction& current,
                                     std::map<Kind, EffectResult>* results,
                                     std::map<Kind, HeldOutPrediction>* admissible,
                                     std::optional<OwnCandidate>* own = nullptr);
  // The sign-flip p of `with`'s improvement on `base`, per 10 s stretch, for candidate `kind`.
  double improvementPValue(const HeldOutPrediction& base, const HeldOutPrediction& with, Kind kind) const;
  // Whether `with` improves on `base` as a name needs (p from improvementPValue): p below the
  // significance, the joint error lower, and the PWM or RPM view's RMSE falling enough, over all
  // blocks or, for a candidate `kind` whose law acts on some only, on those.
  bool improvesEnough(const HeldOutPrediction& base, const HeldOutPrediction& with, double p_value,
                      std::optional<Kind> kind) const;
  // The same for candidate `kind` whose error where its law acts (regionalError) is at hand.
  bool improvesEnough(const HeldOutPrediction& base, const HeldOutPrediction& with, double p_value, Kind kind,
                      const RegionalError& regional) const;
  // p below the significance and the joint error lower.
  bool significantlyLower(const HeldOutPrediction& base, const HeldOutPrediction& with, double p_value) const;
  // The PWM or RPM view's RMSE over all blocks falling enough (fallsEnough).
  bool fallsOverAll(const HeldOutPrediction& base, const HeldOutPrediction& with) const;
  // Why a candidate that lowers nothing enough was not taken, in the numbers the tests used.
  std::string notSignificant(const EffectResult& result, double base_pwm_rmse_pct, double drop_pct,
                             double mean_square_ratio) const;
  void reportEffects(std::map<Kind, EffectResult>* results, const std::vector<Kind>& selected);
  void reportHeldOut(const HeldOutPrediction& before, const HeldOutPrediction& after);
  std::string method() const;
  // "ground_effect 0.140 %": each entry of `thresholds`.
  static std::string regionalThresholds(const std::map<Kind, double>& thresholds);
  // The method line's clause on the RPM view: in use with its weight, or why not.
  std::string rpmView() const;
  std::string dynamicBlocks() const;
  std::string selectionBlocks() const;
  // The samples' three views are the plain model's, taken before the motor balance sets its
  // factors, so that the file's columns stand on one footing (the corrected one has them).
  struct PlainViews {
    std::vector<double> pwm, current, rpm;
  };
  PlainViews plainViews(const effects::ModelEffects& plain) const;
  void collectSamples(const PlainViews& plain);

  const PropulsionModel& model_;
  const Vehicle& vehicle_;
  const std::vector<Flight>& flights_;
  const std::vector<BenchLog>& bench_;
  const DiagnosisConfig& config_;
  ThrustViews views_;
  std::vector<Block> blocks_;
  std::vector<bool> steady_;  // of each block: quasi-steady (not transient with the lag modelled)
  std::vector<const Block*> all_;
  std::vector<int> unit_of_block_;  // the held-out unit (flight or segment) of each block
  std::vector<std::string> unit_names_;  // of each unit: the flight's name, or "flight#segment"
  std::vector<Kind> working_;  // the effects the correction uses: background, selected and ambiguous leaders
  std::vector<Kind> background_;  // the vehicle's own effects, modelled but not named
  std::set<Kind> grouped_;     // members of an ambiguous group: not tried again
  std::map<std::vector<Kind>, FlexibleLaw> flexible_laws_;  // by the effects fitted flexibly
  std::optional<std::string> lacking_motor_law_;  // lackingMotorLaw's, once known
  int units_ = 0;
  std::string unit_name_;
  Diagnosis diagnosis_;
};

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
