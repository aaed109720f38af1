#pragma once

namespace propulsion_estimator {

// The estimate tool: the estimator's onboard session run offline on flight logs (ULog, DataFlash,
// rosbag); see --help and docs/estimate.md.
int runEstimate(int argc, char** argv);

}  // namespace propulsion_estimator
