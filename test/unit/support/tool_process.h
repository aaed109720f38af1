#pragma once
// Running an installed command line as a user runs it, for the tools' process tests.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

/// What a tool run left: its exit status (-1 when it did not exit normally) and its output.
struct ToolRun {
  int status = 0;
  std::string out;
  std::string err;
};

/// The whole text of a file ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// `text` in single quotes for the shell.
inline std::string quoted(const std::string& text) { return "'" + text + "'"; }

/// Runs `tool arguments` through the shell, its stdout and stderr captured in files in `dir`.
inline ToolRun runTool(const std::string& tool, const std::string& arguments, const std::filesystem::path& dir) {
  const std::filesystem::path out = dir / "out.txt", err = dir / "err.txt";
  const std::string command =
      quoted(tool) + " " + arguments + " > " + quoted(out.string()) + " 2> " + quoted(err.string());
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}
