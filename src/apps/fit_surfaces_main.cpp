#include "fit_surfaces_command.h"

int main(int argc, char** argv) { return propulsion_estimator::runFitSurfaces(argc, argv); }
