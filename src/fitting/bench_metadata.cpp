#include "propulsion_estimator/fitting/bench_metadata.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <optional>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace fitting {
namespace {

constexpr char kUnknownName[] = "unknown";

// The one text value the logs agree on for `key`, or the option; nullopt when neither gives one,
// DataError when the logs disagree.
std::optional<std::string> metadataText(const std::vector<BenchLog>& logs, const std::string& key,
                                        const std::optional<std::string>& option) {
  if (option) return option;
  std::optional<std::string> value;
  std::string from;
  for (const BenchLog& log : logs) {
    const auto found = log.metadata.find(key);
    if (found == log.metadata.end()) continue;
    if (value && found->second != *value) {
      throw DataError("logs disagree on " + key + ": '" + *value + "' (" + from + ") and '" + found->second + "' (" +
                      log.source + "); pass --" + key + " to say which the model records");
    }
    value = found->second;
    from = log.source;
  }
  return value;
}

// A name that only describes the combination (esc, motor, propeller): without one the model
// records kUnknownName, and a note says so.
std::string describingName(const std::vector<BenchLog>& logs, const std::string& key,
                           const std::optional<std::string>& option, std::vector<std::string>* notes) {
  if (const std::optional<std::string> name = metadataText(logs, key, option)) return *name;
  notes->push_back(key + ": no log has a '# " + key + ":' line; the model records '" + kUnknownName + "' (pass --" +
                   key + " to name it)");
  return kUnknownName;
}

// One log's value of a bench condition: its metadata line, else the mean of its column; nullopt
// when it gives neither. `origin` names the one used.
std::optional<double> logCondition(const BenchLog& log, const std::string& key, BenchColumn column,
                                   std::string* origin) {
  const auto found = log.metadata.find(key);
  if (found != log.metadata.end()) {
    char* end = nullptr;
    const double value = std::strtod(found->second.c_str(), &end);
    if (end == found->second.c_str() || *end != '\0' || !std::isfinite(value)) {
      throw DataError(log.source + ": metadata " + key + ": '" + found->second + "' is not a number");
    }
    *origin = log.source + " '# " + key + ":'";
    return value;
  }
  if (!log.has(column)) return std::nullopt;
  const std::vector<double>& values = log.column(column);
  *origin = log.source + " column " + benchColumnName(column);
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

// A bench condition: the option, else the mean of the logs' values (logCondition); nullopt when
// none gives it. `origin` says where the value came from, for a refusal of it.
std::optional<double> metadataNumber(const std::vector<BenchLog>& logs, const std::string& key, BenchColumn column,
                                     const std::string& option_name, const std::optional<double>& option,
                                     std::vector<std::string>* notes, std::string* origin) {
  if (option) {
    *origin = "given as " + option_name;
    return option;
  }
  double sum = 0.0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  int count = 0;
  std::vector<std::string> origins;
  for (const BenchLog& log : logs) {
    std::string from;
    const std::optional<double> value = logCondition(log, key, column, &from);
    if (!value) continue;
    origins.push_back(from);
    sum += *value;
    lo = std::min(lo, *value);
    hi = std::max(hi, *value);
    ++count;
  }
  if (count == 0) return std::nullopt;
  if (count > 1 && hi > lo) {
    notes->push_back(key + ": mean of " + std::to_string(count) + " logs (" + formatPrintf("%g", lo) + " to " +
                     formatPrintf("%g", hi) + ")");
  }
  *origin = "from " + nameList(origins, 2) + "; pass " + option_name;
  return sum / count;
}

// What supplies a bench condition, for the refusal that lists the missing ones.
std::string conditionSources(const std::string& key, std::optional<BenchColumn> column) {
  std::string sources = key + " (a '# " + key + ":' line";
  if (column) {
    const std::string name = benchColumnName(*column);
    sources += std::string(" or ") + (name.find_first_of("aeiou") == 0 ? "an " : "a ") + name + " column";
  }
  return sources + ")";
}

// The bench conditions found, and those missing (what would give them, and the options).
struct BenchConditions {
  std::optional<double> temperature_c, pressure_pa;
  std::string temperature_origin, pressure_origin;
  std::optional<std::string> supply;
  std::vector<std::string> missing, missing_options;

  void requireNoneMissing() const {
    if (missing.empty()) return;
    throw DataError("no log gives the bench's " + nameList(missing, missing.size()) + ": pass " +
                    nameList(missing_options, missing_options.size()));
  }
};

// The physics: the air the thrust was measured in and the kind of supply, each from the option
// or the logs; every one missing is recorded, for one refusal that names them all.
BenchConditions findBenchConditions(const std::vector<BenchLog>& logs, const FitOptions& options,
                                    std::vector<std::string>* notes) {
  BenchConditions found;
  found.temperature_c = metadataNumber(logs, "air_temperature_c", BenchColumn::kAmbientTemp, "--air-temperature-c",
                                       options.air_temperature_c, notes, &found.temperature_origin);
  if (!found.temperature_c) {
    found.missing.push_back(conditionSources("air_temperature_c", BenchColumn::kAmbientTemp));
    found.missing_options.push_back("--air-temperature-c");
  }
  found.pressure_pa = metadataNumber(logs, "air_pressure_pa", BenchColumn::kPressure, "--air-pressure-pa",
                                     options.air_pressure_pa, notes, &found.pressure_origin);
  if (!found.pressure_pa) {
    found.missing.push_back(conditionSources("air_pressure_pa", BenchColumn::kPressure));
    found.missing_options.push_back("--air-pressure-pa");
  }
  if (options.supply) {
    found.supply = supplyKindName(*options.supply);
  } else {
    found.supply = metadataText(logs, "supply", std::nullopt);
    if (!found.supply) {
      found.missing.push_back(conditionSources("supply", std::nullopt));
      found.missing_options.push_back("--supply");
    }
  }
  return found;
}

// The bench air, checked as the model loader checks it, so that fit_surfaces never writes a model
// it would refuse.
void setBenchAir(const BenchConditions& found, ModelMetadata* meta) {
  meta->bench_air_temperature_c = *found.temperature_c;
  meta->bench_air_pressure_pa = *found.pressure_pa;
  try {
    meta->validate();
  } catch (const FieldError& e) {
    const bool temperature = e.field() == "metadata.bench_air_temperature_c";
    throw DataError(e.field() + ": " + e.problem() + " (" +
                    (temperature ? found.temperature_origin : found.pressure_origin) + ")");
  }
}

SupplyKind parseSupply(const std::string& supply) {
  if (supply == "battery") return SupplyKind::kBattery;
  if (supply == "regulated") return SupplyKind::kRegulated;
  throw DataError("metadata supply: '" + supply + "' is neither regulated nor battery");
}

// "fit_surfaces from a.csv, b.csv, ... (9 logs)": the file names of the first four logs.
std::string fitSource(const std::vector<BenchLog>& logs) {
  std::string names;
  for (std::size_t l = 0; l < logs.size() && l < 4; ++l) {
    const std::string& path = logs[l].source;
    names += (l ? ", " : "") + path.substr(path.find_last_of('/') + 1);
  }
  if (logs.size() > 4) names += ", ... (" + std::to_string(logs.size()) + " logs)";
  return "fit_surfaces from " + names;
}

}  // namespace

ModelMetadata resolveBenchMetadata(const std::vector<BenchLog>& logs, const FitOptions& options,
                                   std::vector<std::string>* notes) {
  ModelMetadata meta;
  meta.esc = describingName(logs, "esc", options.esc, notes);
  meta.motor = describingName(logs, "motor", options.motor, notes);
  meta.propeller = describingName(logs, "propeller", options.propeller, notes);
  const BenchConditions found = findBenchConditions(logs, options, notes);
  found.requireNoneMissing();
  setBenchAir(found, &meta);
  meta.supply = options.supply ? *options.supply : parseSupply(*found.supply);
  meta.source = fitSource(logs);
  return meta;
}

}  // namespace fitting
}  // namespace propulsion_estimator
