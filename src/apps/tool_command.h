#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace propulsion_estimator {

// Parses the command line of tool `name` and runs it: exit status 2 for a usage error (CLI11
// prints it), 1 with one line "<name>: <reason>" on stderr for a refused input, else what `run`
// returns.
int runToolCommand(const char* name, CLI::App& app, int argc, char** argv, const std::function<int()>& run);

}  // namespace propulsion_estimator
