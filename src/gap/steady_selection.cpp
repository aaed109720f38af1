// The selection runs on the steady blocks alone when transient ones are in: a transient block's
// error also carries what the lag model and the controller leave over, a share that shifts with
// the command and that a mean-shifting effect (esc_offset, thrust_loss) soaks up, naming an effect
// that is not there. What the steady blocks chose is then fitted, and scored, on every block.
#include <set>

#include "diagnoser.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

bool Diagnoser::selectsOnSteadyBlocks() const {
  if (std::find(steady_.begin(), steady_.end(), false) == steady_.end()) return false;
  // Enough steady stretches for the sign-flip test, else the transient blocks are needed too.
  return stretchCount(true) >= fewestGroupsForSignificance(config_.significance);
}

int Diagnoser::stretchCount(bool steady_only) const {
  std::set<std::pair<int, int>> stretches;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    if (steady_[i] || !steady_only) stretches.insert({blocks_[i].flight, blocks_[i].group});
  }
  return static_cast<int>(stretches.size());
}

HeldOutPrediction Diagnoser::select(const HeldOutPrediction& before, std::map<Kind, EffectResult>* results) {
  if (!selectsOnSteadyBlocks()) return selectEffects(before, results);
  Diagnoser steady(*this, steady_, views_);
  steady.selectEffects(steady.predictHeldOut({}), results);
  working_ = steady.working_;
  background_ = steady.background_;
  diagnosis_.background = steady.diagnosis_.background;
  grouped_ = steady.grouped_;
  diagnosis_.selected = steady.diagnosis_.selected;
  diagnosis_.ambiguous = steady.diagnosis_.ambiguous;
  diagnosis_.trace = steady.diagnosis_.trace;
  diagnosis_.current_view_weight = steady.diagnosis_.current_view_weight;
  diagnosis_.rpm_view_weight = steady.diagnosis_.rpm_view_weight;
  diagnosis_.rpm_view_blocks = steady.diagnosis_.rpm_view_blocks;
  for (const std::string& problem : steady.diagnosis_.problems) addProblemOnce(problem);
  return predictHeldOut(working_);
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
