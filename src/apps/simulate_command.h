#pragma once

namespace propulsion_estimator {

// The `simulate` tool: `simulate bench ...` writes a simulated thrust-stand log in the native
// bench CSV, `simulate flight ...` a simulated flight bag and its manifest (options: --help, and
// docs/simulator.md). Returns the process exit status: 0 written, 1 refused, 2 usage error; each failure
// is one line on stderr (tool_command.h).
int runSimulateCommand(int argc, char** argv);

}  // namespace propulsion_estimator
