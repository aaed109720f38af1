#pragma once

#include <functional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

namespace propulsion_estimator {

// Options that parse one by one but do not fit together ("give two or more models"): a usage
// error, exit status 2, like an option CLI11 refuses.
class UsageError : public std::runtime_error {
 public:
  explicit UsageError(const std::string& message) : std::runtime_error(message) {}
};

// Parses the command line of tool `name` and runs it. Every failure is one line on stderr,
// "<name> <subcommand>: <reason>" (the subcommand when one was given): exit status 2 for a usage
// error (CLI11's or a UsageError, with "(see --help)"), 1 for a refused input (InputError) or a
// file system error, and 1 for any other exception ("<name> <subcommand>: internal error: <what>",
// e.g. std::bad_alloc); --help prints the help and exits 0; otherwise the status is what `run`
// returns.
int runToolCommand(const std::string& name, CLI::App& app, int argc, char** argv, const std::function<int()>& run);

// An option's value checked as a number within lo..hi: "abc is not a number" (CLI11's Range calls a
// word out of range), "70 is outside 1..64". wholeNumberIn also refuses a fraction; positiveNumber
// refuses zero and below ("0 is not above 0"; CLI11's PositiveNumber lets NaN through and prints
// the largest double as its range).
CLI::Validator numberIn(double lo, double hi);
CLI::Validator wholeNumberIn(int lo, int hi);
CLI::Validator positiveNumber();

// A path the tool writes, checked before any work: a file to write refuses a folder ("out/: a
// folder, not a file") and a path through a file ("a.csv/m.yaml: a.csv is a file, not a folder");
// a folder to write refuses a file ("a.csv: a file, not a folder"). A missing folder is not
// refused: the tools that write folders create them, fit_surfaces creates --out's.
CLI::Validator fileToWrite();
CLI::Validator folderToWrite();

}  // namespace propulsion_estimator
