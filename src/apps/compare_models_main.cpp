#include "compare_models_command.h"

int main(int argc, char** argv) { return propulsion_estimator::runCompareModels(argc, argv); }
