#include "propulsion_estimator/logs/bench_csv.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <utility>
#include <sstream>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/units.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {
namespace {

// A text cell as CSV needs it: quoted when it holds a delimiter, a quote or a line break.
std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

constexpr const char* kThrustGrams = "thrust_g";

constexpr const char* kSpace = " \t\n\v\f\r";

bool isKeyCharacter(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

/// A comment line's metadata "key: value" (surrounding white space dropped; the key letters,
/// digits and '_'), or nothing for a plain comment. String operations only: a comment line may be
/// arbitrarily long.
std::optional<std::pair<std::string, std::string>> metadataEntry(const std::string& comment) {
  const std::size_t key_begin = comment.find_first_not_of(kSpace);
  if (key_begin == std::string::npos) return std::nullopt;
  std::size_t key_end = key_begin;
  while (key_end < comment.size() && isKeyCharacter(comment[key_end])) ++key_end;
  if (key_end == key_begin) return std::nullopt;
  const std::size_t colon = comment.find_first_not_of(kSpace, key_end);
  if (colon == std::string::npos || comment[colon] != ':') return std::nullopt;
  std::string key = comment.substr(key_begin, key_end - key_begin);
  const std::size_t value_begin = comment.find_first_not_of(kSpace, colon + 1);
  if (value_begin == std::string::npos) return std::make_pair(std::move(key), std::string());
  const std::size_t value_end = comment.find_last_not_of(kSpace) + 1;
  return std::make_pair(std::move(key), comment.substr(value_begin, value_end - value_begin));
}

}  // namespace

void writeNativeBenchCsv(const BenchLog& log, std::ostream& out, ThrustUnit thrust_unit) {
  for (const auto& [key, value] : log.metadata) out << "# " << key << ": " << value << "\n";
  std::vector<int> logged;
  for (int c = 0; c < kBenchColumnCount; ++c) {
    if (!log.columns[c].empty()) logged.push_back(c);
  }
  for (std::size_t k = 0; k < logged.size(); ++k) {
    const auto column = static_cast<BenchColumn>(logged[k]);
    out << (k ? "," : "")
        << (column == BenchColumn::kThrust && thrust_unit == ThrustUnit::kGram ? kThrustGrams
                                                                               : benchColumnName(column));
  }
  for (const auto& extra : log.extra_columns) out << "," << csvField(extra.first);
  out << "\n";
  char buffer[32];
  for (std::size_t row = 0; row < log.rows(); ++row) {
    for (std::size_t k = 0; k < logged.size(); ++k) {
      double value = log.columns[logged[k]][row];
      if (logged[k] == static_cast<int>(BenchColumn::kThrust) && thrust_unit == ThrustUnit::kGram) {
        value /= kNewtonPerGramForce;
      }
      std::snprintf(buffer, sizeof(buffer), "%.6g", value);
      out << (k ? "," : "") << buffer;
    }
    for (const auto& extra : log.extra_columns) out << "," << csvField(extra.second[row]);
    out << "\n";
  }
}

void saveNativeBenchCsv(const BenchLog& log, const std::string& path, ThrustUnit thrust_unit) {
  std::ostringstream text;
  writeNativeBenchCsv(log, text, thrust_unit);
  writeTextFile(path, text.str());
}

bool isNativeBenchHeader(const std::vector<std::string>& header) {
  for (const std::string& name : header) {
    if (name == "pwm_us" || name == "voltage_v" || name == kThrustGrams || name == "thrust_n") return true;
  }
  return false;
}

BenchLog nativeBenchLogFromTable(const CsvText& table, DecimalSeparator decimal) {
  BenchLog log;
  log.source = table.source;
  std::map<std::string, int> metadata_line;
  for (const CsvText::Line& comment : table.comments) {
    std::optional<std::pair<std::string, std::string>> entry = metadataEntry(comment.text);
    if (!entry) continue;
    const std::string& key = entry->first;
    const auto [known, inserted] = metadata_line.emplace(key, comment.line);
    if (!inserted) {
      throw DataError(table.source + ":" + std::to_string(comment.line) + ": metadata key '" + key +
                      "' given twice (first on line " + std::to_string(known->second) + ")");
    }
    log.metadata[key] = std::move(entry->second);
  }

  // Header: which cell column holds which quantity.
  std::array<int, kBenchColumnCount> column_of;
  column_of.fill(-1);
  double thrust_to_newton = 1.0;
  std::map<std::string, std::size_t> seen;
  std::vector<std::size_t> numeric_columns;
  for (std::size_t c = 0; c < table.header.size(); ++c) {
    const std::string& name = table.header[c];
    if (name.empty()) {
      throw DataError(table.source + ":" + std::to_string(table.header_line) + ": column " + std::to_string(c + 1) +
                      " has no name");
    }
    const auto [first, inserted] = seen.emplace(name, c);
    if (!inserted) {
      throw DataError(table.source + ":" + std::to_string(table.header_line) + ": column '" + name +
                      "' appears twice (columns " + std::to_string(first->second + 1) + " and " +
                      std::to_string(c + 1) + ")");
    }
    int quantity = -1;
    for (int q = 0; q < kBenchColumnCount; ++q) {
      if (name == benchColumnName(static_cast<BenchColumn>(q))) quantity = q;
    }
    if (name == kThrustGrams) {
      quantity = static_cast<int>(BenchColumn::kThrust);
      thrust_to_newton = kNewtonPerGramForce;
    }
    if (quantity < 0) continue;
    if (column_of[quantity] >= 0) {
      throw DataError(table.source + ":" + std::to_string(table.header_line) +
                      ": both thrust_g and thrust_n are given; keep one");
    }
    column_of[quantity] = static_cast<int>(c);
    numeric_columns.push_back(c);
  }
  for (BenchColumn required : {BenchColumn::kPwm, BenchColumn::kVoltage, BenchColumn::kThrust}) {
    if (column_of[static_cast<int>(required)] < 0) {
      const std::string name = required == BenchColumn::kThrust ? "thrust_g' or 'thrust_n" : benchColumnName(required);
      throw DataError(table.source + ":" + std::to_string(table.header_line) + ": missing column '" + name +
                      "' (required: pwm_us, voltage_v, and thrust_g or thrust_n)");
    }
  }
  if (table.rows.empty()) throw DataError(table.source + ": no data rows after the header");

  const bool decimal_comma = usesDecimalComma(table, numeric_columns, decimal);
  if (decimal_comma) log.notes.push_back("numbers read with a decimal comma (';'-separated file)");
  for (int q = 0; q < kBenchColumnCount; ++q) {
    if (column_of[q] < 0) continue;
    std::optional<std::vector<double>> values = numericColumn(table, column_of[q], decimal_comma);
    if (!values) {
      const auto column = static_cast<BenchColumn>(q);
      if (column == BenchColumn::kPwm || column == BenchColumn::kVoltage || column == BenchColumn::kThrust) {
        throw DataError(table.source + ":" + std::to_string(table.header_line) + ": column '" +
                        table.header[column_of[q]] + "' has no values");
      }
      continue;
    }
    if (q == static_cast<int>(BenchColumn::kThrust)) {
      for (double& value : *values) value *= thrust_to_newton;
    }
    log.columns[q] = std::move(*values);
  }
  for (std::size_t c = 0; c < table.header.size(); ++c) {
    if (std::find(numeric_columns.begin(), numeric_columns.end(), c) != numeric_columns.end()) continue;
    std::vector<std::string>& extra = log.extra_columns[table.header[c]];
    for (const CsvText::Row& row : table.rows) extra.push_back(row.fields[c]);
  }
  for (const CsvText::Row& row : table.rows) log.line_numbers.push_back(row.line);
  return log;
}

BenchLog parseNativeBenchCsv(const std::string& text, const std::string& source) {
  const CsvText table = splitCsvText(text, source);
  if (!isNativeBenchHeader(table.header)) {
    throw DataError(source + ":" + std::to_string(table.header_line) +
                    ": missing column 'pwm_us' (required: pwm_us, voltage_v, and thrust_g or thrust_n)");
  }
  return nativeBenchLogFromTable(table);
}

}  // namespace propulsion_estimator
