#include "tool_command.h"

#include <cstdio>
#include <filesystem>

#include "propulsion_estimator/common/input_error.h"

namespace propulsion_estimator {

int runToolCommand(const char* name, CLI::App& app, int argc, char** argv, const std::function<int()>& run) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    return run();
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
  }
  return 1;
}

}  // namespace propulsion_estimator
