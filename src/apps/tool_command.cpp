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

namespace {

// `T` read from the option's text within lo..hi; `what` names a text that is no `T`.
template <typename T>
CLI::Validator valueIn(T lo, T hi, const std::string& range, const std::string& what, const std::string& kind) {
  return CLI::Validator(
      [lo, hi, range, what](std::string& text) -> std::string {
        T value{};
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(static_cast<double>(value))) {
          return text + " is not " + what;
        }
        if (value < lo || value > hi) return text + " is outside " + range;
        return "";
      },
      kind + " in " + range);
}

}  // namespace

CLI::Validator numberIn(double lo, double hi) {
  return valueIn(lo, hi, formatNumber(lo) + ".." + formatNumber(hi), "a number", "NUMBER");
}

CLI::Validator wholeNumberIn(int lo, int hi) {
  return valueIn<long long>(lo, hi, std::to_string(lo) + ".." + std::to_string(hi), "a whole number", "INT");
}

CLI::Validator positiveNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value)) return text + " is not a number";
        if (!(value > 0.0)) return text + " is not above 0";
        return "";
      },
      "NUMBER > 0");
}

namespace {

// The refusal of `path` when some folder on its way is a file, else "".
std::string throughAFile(const std::filesystem::path& path) {
  std::error_code error;
  for (std::filesystem::path folder = path.parent_path(); !folder.empty() && folder != folder.root_path();
       folder = folder.parent_path()) {
    if (std::filesystem::exists(folder, error) && !std::filesystem::is_directory(folder, error)) {
      return path.string() + ": " + folder.string() + " is a file, not a folder";
    }
  }
  return "";
}

}  // namespace

CLI::Validator fileToWrite() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::error_code error;
        if (std::filesystem::is_directory(text, error) || (!text.empty() && text.back() == '/')) {
          return text + ": a folder, not a file";
        }
        return throughAFile(text);
      },
      "FILE");
}

CLI::Validator folderToWrite() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::error_code error;
        if (std::filesystem::exists(text, error) && !std::filesystem::is_directory(text, error)) {
          return text + ": a file, not a folder";
        }
        return throughAFile(std::filesystem::path(text) / "x");
      },
      "DIR");
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
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s (see --help)\n", commandName(name, app).c_str(), e.what());
    return 2;
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
