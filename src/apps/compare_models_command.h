#pragma once

namespace propulsion_estimator {

// `compare_models [options] MODEL.yaml[=LOG[,LOG...]] ...`: thesis chapter 7's table of two or
// more combinations (printed as Markdown), their hover point and endurance on a battery, and a
// report with comparison figures. Returns 0, 1 (refused, message on stderr) or 2 (usage).
int runCompareModels(int argc, char** argv);

}  // namespace propulsion_estimator
