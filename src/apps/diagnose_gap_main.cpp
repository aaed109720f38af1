#include "diagnose_gap_command.h"

int main(int argc, char** argv) { return propulsion_estimator::runDiagnoseGap(argc, argv); }
