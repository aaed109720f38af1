#include "estimate_command.h"

int main(int argc, char** argv) { return propulsion_estimator::runEstimate(argc, argv); }
