#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/logs/bench_log.h"
#include "propulsion_estimator/logs/bench_read_options.h"
#include "propulsion_estimator/logs/csv_text.h"

namespace propulsion_estimator {

/// The bench log formats the reader knows: the package's native CSV and RCbenchmark/Tyto's export.
enum class BenchLogFormat { kNative, kTyto };

/// Detects the format from the header (native column names, or an RCbenchmark/Tyto "ESC signal"
/// column) and reads the log. What the reader decided (a negated thrust, the rpm column it took,
/// decimal commas) is appended to BenchLog::notes. Throws DataError naming the file, and the line
/// and column where one is at fault (InputError for a file that cannot be read).
BenchLog parseBenchLog(const std::string& text, const std::string& source, const BenchReadOptions& options);
/// Reads the log file `path` as parseBenchLog reads its text; InputError when it cannot be read.
BenchLog readBenchLog(const std::string& path, const BenchReadOptions& options = {});
/// The format of a split table from its header; DataError naming the header line when it is neither.
BenchLogFormat detectBenchLogFormat(const CsvText& table);

/// One log file of the command line, and the later arguments that named it again (a file and its
/// directory, a symbolic link; compared as canonical paths): it is read once, or it would count
/// twice in the fit and sit on both sides of a cross-validation fold.
struct BenchLogFile {
  std::string path;                        ///< as first named (an argument, or a file of a directory)
  std::vector<std::string> also_named_by;  ///< arguments (files or directories) that named it again
};

/// Command-line log arguments to files: a file stays, a directory stands for its *.csv files
/// (sorted by name, not recursive), each file once. Throws InputError for a missing path or an
/// empty directory.
std::vector<BenchLogFile> expandBenchLogPaths(const std::vector<std::string>& arguments);

/// The BenchColumn named by its native name ("rpm", "motor_temp_c", "thrust_n"); ConfigError
/// listing the names when there is none.
BenchColumn benchColumnFromName(const std::string& name);

}  // namespace propulsion_estimator
