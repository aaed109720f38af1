#include "propulsion_estimator/estimation/tare_verdict.h"

#include <cmath>
#include <sstream>

namespace propulsion_estimator {

TareVerdict judgeTare(const HoverVerdict& hover, const MassEstimate& estimate, const EstimatorConfig& config) {
  TareVerdict verdict;
  if (!hover.hovering) {
    verdict.refusal = "refused: " + describe(hover, config.hover);
  } else if (std::isnan(estimate.total_mass_kg)) {
    std::ostringstream message;
    message << "refused: hovering, but only " << estimate.window_samples << " of the " << config.payload.min_samples
            << " hover samples needed are averaged yet";
    verdict.refusal = message.str();
  } else {
    verdict.accepted = true;
  }
  return verdict;
}

}  // namespace propulsion_estimator
