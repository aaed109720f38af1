#pragma once

#include <string>

#include "propulsion_estimator/offline/flight_estimate.h"

namespace propulsion_estimator {
namespace offline {

/// The Markdown summary `estimate` writes beside its table (summary.md): the log and the model, the
/// hover episodes with their mass, payload and capability, the motor-health verdict, the inputs
/// accepted and refused, and every warning; `figure` is the PNG it shows ("" for none).
std::string estimateSummaryMarkdown(const FlightEstimate& estimate, const std::string& model_name,
                                    const std::string& figure);

}  // namespace offline
}  // namespace propulsion_estimator
