#include "propulsion_estimator/logs/tyto_csv.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace {

constexpr double kNewtonPerPoundForce = 4.4482216152605;
constexpr double kNewtonPerOunceForce = kNewtonPerPoundForce / 16.0;
// Below this share of the other sign's largest magnitude, values of the "wrong" sign are taken
// for zero-point noise of a sensor at rest (a load cell reads -1 gf at idle).
constexpr double kSignNoiseShare = 0.05;

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

// "Thrust (kgf)" -> {"thrust", "kgf"}; a name without "(unit)" has an empty unit.
std::pair<std::string, std::string> nameAndUnit(const std::string& header) {
  const std::size_t open = header.rfind('(');
  const std::size_t close = header.rfind(')');
  if (open == std::string::npos || close == std::string::npos || close < open) return {lower(header), ""};
  std::string name = header.substr(0, open);
  while (!name.empty() && name.back() == ' ') name.pop_back();
  return {lower(name), header.substr(open + 1, close - open - 1)};
}

bool isMicroseconds(const std::string& unit) {
  return unit == "\xC2\xB5s" || unit == "\xCE\xBCs" || unit == "us";  // micro sign, Greek mu, ASCII
}

// Multiplier to the BenchLog unit of `quantity` for a column's unit; nullopt when unknown.
std::optional<double> toLogUnit(BenchColumn quantity, const std::string& unit) {
  switch (quantity) {
    case BenchColumn::kThrust:
      if (unit == "N") return 1.0;
      if (unit == "kgf") return kStandardGravity;
      if (unit == "gf" || unit == "g") return kNewtonPerGramForce;
      if (unit == "lbf") return kNewtonPerPoundForce;
      if (unit == "ozf") return kNewtonPerOunceForce;
      return std::nullopt;
    case BenchColumn::kPwm:
      return isMicroseconds(unit) ? std::optional<double>(1.0) : std::nullopt;
    case BenchColumn::kTime:
      return unit == "s" ? std::optional<double>(1.0) : std::nullopt;
    case BenchColumn::kVoltage:
      return unit == "V" ? std::optional<double>(1.0) : std::nullopt;
    case BenchColumn::kCurrent:
      return unit == "A" ? std::optional<double>(1.0) : std::nullopt;
    case BenchColumn::kPower:
      return unit == "W" ? std::optional<double>(1.0) : std::nullopt;
    case BenchColumn::kRpm:
      return lower(unit) == "rpm" ? std::optional<double>(1.0) : std::nullopt;
    case BenchColumn::kAmbientTemp:
    case BenchColumn::kMotorTemp:
      // degree sign, masculine ordinal (RCbenchmark writes "ºC"), or plain
      if (unit ==
              "\xC2\xB0"
              "C" ||
          unit ==
              "\xC2\xBA"
              "C" ||
          unit == "C" || unit == "degC")
        return 1.0;
      return std::nullopt;
    case BenchColumn::kPressure:
      if (unit == "Pa") return 1.0;
      if (unit == "hPa" || unit == "mbar") return 100.0;
      if (unit == "kPa") return 1000.0;
      return std::nullopt;
  }
  return std::nullopt;
}

// Which header names the format gives each quantity (lower case, without the unit).
std::vector<std::string> standardNames(BenchColumn quantity) {
  switch (quantity) {
    case BenchColumn::kTime:
      return {"time"};
    case BenchColumn::kPwm:
      return {"esc signal"};
    case BenchColumn::kVoltage:
      return {"voltage"};
    case BenchColumn::kThrust:
      return {"thrust"};
    case BenchColumn::kCurrent:
      return {"current"};
    case BenchColumn::kPower:
      return {"electrical power"};
    case BenchColumn::kRpm:
      return {"motor electrical speed", "motor optical speed"};
    default:
      return {};
  }
}

std::string formatValue(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4g", value);
  return buffer;
}

// Applies a sign policy to one column; says what it did in `notes`.
void applySign(const CsvText& table, const std::string& header, const std::string& option, SignPolicy policy,
               std::vector<double>* values, std::vector<std::string>* notes) {
  if (policy == SignPolicy::kAsLogged) return;
  const auto [low, high] = std::minmax_element(values->begin(), values->end());
  const double positive = std::max(0.0, *high);
  const double negative = std::max(0.0, -*low);
  const std::string range = "from " + formatValue(*low) + " to " + formatValue(*high);
  if (policy == SignPolicy::kAuto) {
    if (negative <= kSignNoiseShare * positive) return;
    if (positive > kSignNoiseShare * negative) {
      throw DataError(table.source + ": column '" + header + "' has both signs (" + range +
                      "): say how the stand was mounted with " + option + " as-logged or " + option + " negate");
    }
  }
  for (double& value : *values) value = -value;
  notes->push_back("'" + header + "' negated (" + range + " as logged" +
                   (policy == SignPolicy::kAuto ? ", logged negative as a pusher mounting or reversed sensor gives)"
                                                : ", " + option + " negate)"));
}

}  // namespace

bool isTytoHeader(const std::vector<std::string>& header) {
  for (const std::string& column : header) {
    const auto [name, unit] = nameAndUnit(column);
    if (name == "esc signal" && isMicroseconds(unit)) return true;
  }
  return false;
}

BenchLog tytoBenchLogFromTable(const CsvText& table, const BenchReadOptions& options) {
  BenchLog log;
  log.source = table.source;
  const std::string header_where = table.source + ":" + std::to_string(table.header_line);
  if (table.rows.empty()) throw DataError(table.source + ": no data rows after the header");

  // Candidate columns of each quantity: the user's choice, else the format's names.
  std::array<std::vector<std::size_t>, kBenchColumnCount> candidates;
  for (int q = 0; q < kBenchColumnCount; ++q) {
    const auto quantity = static_cast<BenchColumn>(q);
    const auto chosen = options.columns.find(quantity);
    if (chosen != options.columns.end()) {
      const auto at = std::find(table.header.begin(), table.header.end(), chosen->second);
      if (at == table.header.end()) {
        throw DataError(header_where + ": no column '" + chosen->second + "' for " + benchColumnName(quantity) +
                        " (--map " + benchColumnName(quantity) + "=...)");
      }
      candidates[q] = {static_cast<std::size_t>(at - table.header.begin())};
      continue;
    }
    const std::vector<std::string> names = standardNames(quantity);
    for (std::size_t c = 0; c < table.header.size(); ++c) {
      if (std::find(names.begin(), names.end(), nameAndUnit(table.header[c]).first) != names.end()) {
        candidates[q].push_back(c);
      }
    }
  }

  std::vector<std::size_t> numeric_columns;
  for (const auto& columns : candidates) numeric_columns.insert(numeric_columns.end(), columns.begin(), columns.end());
  const bool decimal_comma = usesDecimalComma(table, numeric_columns, options.decimal);
  if (decimal_comma) log.notes.push_back("numbers read with a decimal comma (';'-separated file)");

  std::vector<bool> used(table.header.size(), false);
  for (int q = 0; q < kBenchColumnCount; ++q) {
    const auto quantity = static_cast<BenchColumn>(q);
    const std::string quantity_name = benchColumnName(quantity);
    const bool required =
        quantity == BenchColumn::kPwm || quantity == BenchColumn::kVoltage || quantity == BenchColumn::kThrust;
    // Columns of this quantity that hold values. An optional sensor that is not connected logs
    // zeros or nothing; a required one that does is refused later as a constant column.
    std::vector<std::pair<std::size_t, std::vector<double>>> logged;
    std::vector<std::string> silent;
    for (std::size_t c : candidates[q]) {
      std::optional<std::vector<double>> values = numericColumn(table, c, decimal_comma);
      const bool all_zero = values && std::all_of(values->begin(), values->end(), [](double v) { return v == 0.0; });
      if (values && (required || !all_zero)) {
        logged.emplace_back(c, std::move(*values));
      } else {
        silent.push_back("'" + table.header[c] + "' is " + (values ? "zero" : "empty") + " in every row");
      }
    }
    if (logged.empty()) {
      if (required) {
        const std::string what = candidates[q].empty() ? "missing column" : "no values in the column";
        const std::string names = quantity == BenchColumn::kPwm       ? "ESC signal (\xC2\xB5s)"
                                  : quantity == BenchColumn::kVoltage ? "Voltage (V)"
                                                                      : "Thrust (kgf, gf, N, lbf or ozf)";
        throw DataError(header_where + ": " + what + " '" + names + "'");
      }
      if (!silent.empty()) log.notes.push_back("no " + quantity_name + ": " + silent.front());
      continue;
    }
    if (logged.size() > 1) {
      throw DataError(header_where + ": two " + quantity_name + " columns with values, '" +
                      table.header[logged[0].first] + "' and '" + table.header[logged[1].first] +
                      "': choose one with --map " + quantity_name + "=<column>");
    }
    auto& [column, values] = logged.front();
    const std::string unit = nameAndUnit(table.header[column]).second;
    const std::optional<double> factor = toLogUnit(quantity, unit);
    if (!factor) {
      throw DataError(header_where + ": column '" + table.header[column] + "': unit '" + unit + "' is not a unit of " +
                      quantity_name);
    }
    if (quantity == BenchColumn::kThrust) {
      applySign(table, table.header[column], "--thrust-sign", options.thrust_sign, &values, &log.notes);
    } else if (quantity == BenchColumn::kCurrent || quantity == BenchColumn::kPower) {
      applySign(table, table.header[column], "--current-sign", options.current_sign, &values, &log.notes);
    }
    for (double& value : values) value *= *factor;
    if (candidates[q].size() > 1) {
      log.notes.push_back(quantity_name + " from '" + table.header[column] + "'; " + silent.front());
    }
    if (quantity == BenchColumn::kRpm && nameAndUnit(table.header[column]).first == "motor electrical speed") {
      log.notes.push_back(
          "rpm is the motor's electrical speed: mechanical rpm only if the stand software knew "
          "the motor's pole count");
    }
    used[column] = true;
    log.columns[q] = std::move(values);
  }
  for (std::size_t c = 0; c < table.header.size(); ++c) {
    if (used[c] || table.header[c].empty()) continue;
    std::vector<std::string>& extra = log.extra_columns[table.header[c]];
    for (const CsvText::Row& row : table.rows) extra.push_back(row.fields[c]);
  }
  for (const CsvText::Row& row : table.rows) log.line_numbers.push_back(row.line);
  return log;
}

}  // namespace propulsion_estimator
