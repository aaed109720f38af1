#include "propulsion_estimator/logs/bench_log_reader.h"

#include <algorithm>
#include <filesystem>
#include <map>

#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/logs/bench_csv.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/logs/tyto_csv.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {

BenchLogFormat detectBenchLogFormat(const CsvText& table) {
  if (isNativeBenchHeader(table.header)) return BenchLogFormat::kNative;
  if (isTytoHeader(table.header)) return BenchLogFormat::kTyto;
  throw DataError(table.source + ":" + std::to_string(table.header_line) +
                  ": not a bench log: the header has neither the native columns (pwm_us, voltage_v, thrust_g or "
                  "thrust_n) nor an RCbenchmark/Tyto 'ESC signal (\xC2\xB5s)' column");
}

BenchLog parseBenchLog(const std::string& text, const std::string& source, const BenchReadOptions& options) {
  const CsvText table = splitCsvText(text, source);
  BenchLog log = detectBenchLogFormat(table) == BenchLogFormat::kNative
                     ? nativeBenchLogFromTable(table, options.decimal)
                     : tytoBenchLogFromTable(table, options);
  if (table.had_byte_order_mark) log.notes.insert(log.notes.begin(), "UTF-8 byte-order mark skipped");
  return log;
}

BenchLog readBenchLog(const std::string& path, const BenchReadOptions& options) {
  return parseBenchLog(readTextFile(path), path, options);
}

std::vector<BenchLogFile> expandBenchLogPaths(const std::vector<std::string>& arguments) {
  namespace fs = std::filesystem;
  std::vector<BenchLogFile> files;
  std::map<fs::path, std::size_t> index;  // canonical path -> files
  auto add = [&](const std::string& path, const std::string& argument) {
    const auto [known, inserted] = index.emplace(fs::canonical(path), files.size());
    if (inserted) {
      files.push_back({path, {}});
    } else {
      files[known->second].also_named_by.push_back(argument);
    }
  };
  for (const std::string& argument : arguments) {
    std::error_code error;
    const fs::file_status status = fs::status(argument, error);
    if (!fs::exists(status)) throw InputError(argument + ": no such file or directory");
    if (!fs::is_directory(status)) {
      add(argument, argument);
      continue;
    }
    std::vector<std::string> found;
    for (const fs::directory_entry& entry : fs::directory_iterator(argument)) {
      if (entry.is_regular_file() && entry.path().extension() == ".csv") found.push_back(entry.path().string());
    }
    if (found.empty()) throw InputError(argument + ": directory has no *.csv files");
    std::sort(found.begin(), found.end());
    for (const std::string& path : found) add(path, argument);
  }
  return files;
}

BenchColumn benchColumnFromName(const std::string& name) {
  std::string known;
  for (int q = 0; q < kBenchColumnCount; ++q) {
    const auto column = static_cast<BenchColumn>(q);
    if (name == benchColumnName(column)) return column;
    known += std::string(q ? ", " : "") + benchColumnName(column);
  }
  throw ConfigError("'" + name + "' is not a bench quantity (one of " + known + ")");
}

}  // namespace propulsion_estimator
