#pragma once

namespace propulsion_estimator {

// The `simulate` tool: `simulate bench ...` writes a simulated thrust-stand log in the native
// bench CSV, `simulate flight ...` a simulated flight bag and its manifest (options: --help, and
// the README). Returns the process exit code; refusals are one line on stderr.
int runSimulateCommand(int argc, char** argv);

}  // namespace propulsion_estimator
