#pragma once

#include <string>

#include "propulsion_estimator/estimation/estimator_config.h"
#include "propulsion_estimator/estimation/hover_detector.h"
#include "propulsion_estimator/estimation/payload_estimator.h"

namespace propulsion_estimator {

/// Whether a tare would be accepted now, and if not why.
struct TareVerdict {
  bool accepted = false;  ///< whether a tare would be accepted now
  std::string refusal;  ///< "refused: <why>"; empty when accepted
};

/// A tare needs a hover and a hover average of at least payload/min_samples samples. Throws nothing.
TareVerdict judgeTare(const HoverVerdict& hover, const MassEstimate& estimate, const EstimatorConfig& config);

}  // namespace propulsion_estimator
