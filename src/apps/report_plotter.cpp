#include "report_plotter.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "propulsion_estimator/common/config_error.h"

extern char** environ;

namespace propulsion_estimator {
namespace {

constexpr const char* kScriptName = "plot_bench_report.py";
constexpr const char* kDebianPython = "/usr/bin/python3";

// Runs a program (searched on PATH) with its output going to ours, or its error output
// discarded when `quiet`; its exit status, or -1 when it could not be started.
int run(const std::vector<std::string>& arguments, bool quiet) {
  std::vector<char*> argv;
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet) posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t child = 0;
  const int spawned = posix_spawnp(&child, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  if (waitpid(child, &status, 0) != child || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

std::string findScript(const std::string& script) {
  namespace fs = std::filesystem;
  if (!script.empty()) {
    if (!fs::exists(script)) throw ConfigError(script + ": plot script not found (--plot-script)");
    if (fs::is_directory(script)) throw ConfigError(script + ": a folder, not the plot script (--plot-script)");
    return script;
  }
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  const fs::path beside = self.parent_path() / kScriptName;
  if (error || !fs::exists(beside)) {
    throw ConfigError(std::string(kScriptName) + " not found next to this executable (" + beside.string() +
                      "): pass --plot-script PATH");
  }
  return beside.string();
}

// Where the shell would find `program`: itself when it names a path, else the first executable
// of that name on PATH (empty when there is none).
std::string onPath(const std::string& program) {
  if (program.find('/') != std::string::npos) return program;
  const char* path = std::getenv("PATH");
  std::string directories = path ? path : "";
  for (std::size_t start = 0; start <= directories.size();) {
    std::size_t colon = directories.find(':', start);
    if (colon == std::string::npos) colon = directories.size();
    const std::string candidate = directories.substr(start, colon - start) + "/" + program;
    if (colon > start && access(candidate.c_str(), X_OK) == 0) return candidate;
    start = colon + 1;
  }
  return "";
}

bool hasMatplotlib(const std::string& python) { return run({python, "-c", "import matplotlib, numpy"}, true) == 0; }

}  // namespace

void ReportPlotter::check() const {
  findScript(script_);
  const int status = run({python_, "-c", "import matplotlib, numpy"}, true);
  if (status == 0) return;
  const std::string found = onPath(python_);
  const std::string named = found.empty() || found == python_ ? python_ : python_ + " (" + found + ")";
  // Debian's interpreter is the one scripts/install_deps.sh gives matplotlib; a pyenv or venv
  // python3 first on PATH usually lacks it.
  const std::string debian = kDebianPython;
  std::string advice;
  if (found == debian) {
    advice = "install Debian's python3-matplotlib (scripts/install_deps.sh)";
  } else if (hasMatplotlib(debian)) {
    advice = "pass --python " + debian + ", which has them";
  } else {
    advice = "install Debian's python3-matplotlib (scripts/install_deps.sh) and pass --python " + debian;
  }
  throw ConfigError(named + (status < 0 ? " cannot be run" : " cannot import matplotlib and numpy") +
                    ", which the report's figures need: " + advice);
}

void ReportPlotter::addTo(CLI::App& app) {
  app.add_option("--python", python_, "Python interpreter with matplotlib, for the report's figures")
      ->capture_default_str();
  app.add_option("--plot-script", script_, "plot_bench_report.py (default: next to this executable)");
}

void ReportPlotter::plot(const std::string& mode, const std::string& directory) const {
  check();
  const std::string path = findScript(script_);
  const int status = run({python_, path, mode, directory}, false);
  if (status != 0)
    throw ConfigError(path + " " + mode + " " + directory + " failed (exit status " + std::to_string(status) + ")");
}

}  // namespace propulsion_estimator
