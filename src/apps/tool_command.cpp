#include "tool_command.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {

namespace {

// The tool's name and the subcommand the command line chose, for messages: "simulate bench".
std::string commandName(const std::string& name, const CLI::App& app) {
  std::string command = name;
  for (const CLI::App* subcommand : app.get_subcommands()) command += " " + subcommand->get_name();
  return command;
}

}  // namespace

CLI::Validator numberIn(double lo, double hi) {
  const std::string range = formatNumber(lo) + ".." + formatNumber(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value)) return text + " is not a number";
        if (value < lo || value > hi) return text + " is outside " + range;
        return "";
      },
      "NUMBER in " + range);
}

CLI::Validator wholeNumberIn(int lo, int hi) {
  const std::string range = std::to_string(lo) + ".." + std::to_string(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        long long value = 0;
        if (!CLI::detail::lexical_cast(text, value)) return text + " is not a whole number";
        if (value < lo || value > hi) return text + " is outside " + range;
        return "";
      },
      "INT in " + range);
}

int runToolCommand(const std::string& name, CLI::App& app, int argc, char** argv, const std::function<int()>& run) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);  // --help
    std::fprintf(stderr, "%s: %s (see --help)\n", commandName(name, app).c_str(), e.what());
    return 2;
  }
  try {
    return run();
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: %s\n", commandName(name, app).c_str(), e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    std::fprintf(stderr, "%s: %s\n", commandName(name, app).c_str(), e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", commandName(name, app).c_str(), e.what());
  }
  return 1;
}

}  // namespace propulsion_estimator
