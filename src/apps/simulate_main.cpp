// Physics simulator of the propulsion chain: thrust-stand logs and flight bags with ground truth.
#include "simulate_command.h"

int main(int argc, char** argv) { return propulsion_estimator::runSimulateCommand(argc, argv); }
