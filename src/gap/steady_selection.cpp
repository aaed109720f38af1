// The selection runs on the steady blocks inside the model's domain when others are in. A
// transient block's error also carries what the lag model and the controller leave over, a share
// that shifts with the command and that a mean-shifting effect (esc_offset, thrust_loss) soaks up,
// naming an effect that is not there. Outside the domain the model's value is its policy's (the
// node's clamp, or the surfaces' extrapolation), where the bench measured nothing: its error there
// follows no effect's law. What the kept blocks chose is then fitted, and scored, on every block.
#include <algorithm>
#include <array>
#include <set>

#include "diagnoser.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

std::vector<bool> Diagnoser::selectionMask() const {
  std::vector<bool> steady_inside(blocks_.size());
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    steady_inside[i] = steady_[i] && insideDomain(blocks_[i], model_.domain(), motorCount());
  }
  const int needed = fewestGroupsForSignificance(config_.significance);
  for (const std::vector<bool>* mask : std::array<const std::vector<bool>*, 2>{&steady_inside, &steady_}) {
    // Enough stretches for the sign-flip test, else the left-out blocks are needed too.
    if (std::find(mask->begin(), mask->end(), false) != mask->end() && stretchCount(*mask) >= needed) return *mask;
  }
  return {};
}

int Diagnoser::stretchCount(const std::vector<bool>& mask) const {
  std::set<std::pair<int, int>> stretches;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    if (mask.empty() || mask[i]) stretches.insert({blocks_[i].flight, blocks_[i].group});
  }
  return static_cast<int>(stretches.size());
}

HeldOutPrediction Diagnoser::select(const HeldOutPrediction& before, std::map<Kind, EffectResult>* results) {
  const std::vector<bool> mask = selectionMask();
  if (mask.empty()) return selectEffects(before, results);
  Diagnoser kept(*this, mask, views_);
  kept.selectEffects(kept.predictHeldOut({}), results);
  working_ = kept.working_;
  background_ = kept.background_;
  diagnosis_.background = kept.diagnosis_.background;
  grouped_ = kept.grouped_;
  diagnosis_.selected = kept.diagnosis_.selected;
  diagnosis_.ambiguous = kept.diagnosis_.ambiguous;
  diagnosis_.trace = kept.diagnosis_.trace;
  diagnosis_.current_view_weight = kept.diagnosis_.current_view_weight;
  diagnosis_.rpm_view_weight = kept.diagnosis_.rpm_view_weight;
  diagnosis_.rpm_view_blocks = kept.diagnosis_.rpm_view_blocks;
  for (const std::string& problem : kept.diagnosis_.problems) addProblemOnce(problem);
  return predictHeldOut(working_);
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
