#pragma once

namespace propulsion_estimator {

// `fit_surfaces --out MODEL.yaml [--report DIR] [options] LOG...`: bench logs (files or
// directories of *.csv) to a model file the estimator loads, and a report with figures.
// Returns the process exit status: 0 written, 1 refused (message on stderr), 2 usage error.
int runFitSurfaces(int argc, char** argv);

}  // namespace propulsion_estimator
