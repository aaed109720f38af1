#include "propulsion_estimator/fitting/surface_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/fitting/grouped_least_squares.h"
#include "propulsion_estimator/model/model_validation.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/model/polynomial_2d.h"

namespace propulsion_estimator {
namespace fitting {
namespace {

constexpr char kUnknownName[] = "unknown";

const char* fileUnit(Output output) {
  switch (output) {
    case Output::kThrust:
      return "g";
    case Output::kCurrent:
      return "A";
    case Output::kPower:
      return "W";
    case Output::kEfficiency:
      return "g/W";
    case Output::kRpm:
      return "rpm";
  }
  return "";
}

// "a, b and c" for up to `shown` names, then "a, b and 3 more".
std::string nameList(const std::vector<std::string>& names, std::size_t shown) {
  std::string text;
  const std::size_t listed = names.size() > shown + 1 ? shown : names.size();
  for (std::size_t k = 0; k < listed; ++k) {
    text += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
  }
  if (listed < names.size()) text += " and " + std::to_string(names.size() - listed) + " more";
  return text;
}

// ---- metadata ---------------------------------------------------------------------------------

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

// A bench condition: the option, else the mean of the logs' metadata values, else the mean of
// a logged column; nullopt when none gives it. `origin` says where the value came from, for a
// refusal of it.
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
    const auto found = log.metadata.find(key);
    double value = kNaN;
    if (found != log.metadata.end()) {
      char* end = nullptr;
      value = std::strtod(found->second.c_str(), &end);
      if (end == found->second.c_str() || *end != '\0' || !std::isfinite(value)) {
        throw DataError(log.source + ": metadata " + key + ": '" + found->second + "' is not a number");
      }
      origins.push_back(log.source + " '# " + key + ":'");
    } else if (log.has(column)) {
      const std::vector<double>& values = log.column(column);
      value = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
      origins.push_back(log.source + " column " + benchColumnName(column));
    } else {
      continue;
    }
    sum += value;
    lo = std::min(lo, value);
    hi = std::max(hi, value);
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

ModelMetadata resolveMetadata(const std::vector<BenchLog>& logs, const FitOptions& options,
                              std::vector<std::string>* notes) {
  ModelMetadata meta;
  meta.esc = describingName(logs, "esc", options.esc, notes);
  meta.motor = describingName(logs, "motor", options.motor, notes);
  meta.propeller = describingName(logs, "propeller", options.propeller, notes);
  // The physics: the air the thrust was measured in and the kind of supply. Every one missing is
  // named at once.
  std::vector<std::string> missing, missing_options;
  std::string temperature_origin, pressure_origin;
  const std::optional<double> temperature_c =
      metadataNumber(logs, "air_temperature_c", BenchColumn::kAmbientTemp, "--air-temperature-c",
                     options.air_temperature_c, notes, &temperature_origin);
  if (!temperature_c) {
    missing.push_back(conditionSources("air_temperature_c", BenchColumn::kAmbientTemp));
    missing_options.push_back("--air-temperature-c");
  }
  const std::optional<double> pressure_pa =
      metadataNumber(logs, "air_pressure_pa", BenchColumn::kPressure, "--air-pressure-pa", options.air_pressure_pa,
                     notes, &pressure_origin);
  if (!pressure_pa) {
    missing.push_back(conditionSources("air_pressure_pa", BenchColumn::kPressure));
    missing_options.push_back("--air-pressure-pa");
  }
  std::optional<std::string> supply;
  if (!options.supply) {
    supply = metadataText(logs, "supply", std::nullopt);
    if (!supply) {
      missing.push_back(conditionSources("supply", std::nullopt));
      missing_options.push_back("--supply");
    }
  }
  if (!missing.empty()) {
    throw DataError("no log gives the bench's " + nameList(missing, missing.size()) + ": pass " +
                    nameList(missing_options, missing_options.size()));
  }
  meta.bench_air_temperature_c = *temperature_c;
  meta.bench_air_pressure_pa = *pressure_pa;
  // The loader's own check, so that fit_surfaces never writes a model it would refuse.
  try {
    meta.validate();
  } catch (const FieldError& e) {
    const bool temperature = e.field() == "metadata.bench_air_temperature_c";
    throw DataError(e.field() + ": " + e.problem() + " (" + (temperature ? temperature_origin : pressure_origin) + ")");
  }
  if (options.supply) {
    meta.supply = *options.supply;
  } else if (*supply == "regulated" || *supply == "battery") {
    meta.supply = *supply == "battery" ? SupplyKind::kBattery : SupplyKind::kRegulated;
  } else {
    throw DataError("metadata supply: '" + *supply + "' is neither regulated nor battery");
  }
  std::string names;
  for (std::size_t l = 0; l < logs.size() && l < 4; ++l) {
    const std::string& path = logs[l].source;
    names += (l ? ", " : "") + path.substr(path.find_last_of('/') + 1);
  }
  if (logs.size() > 4) names += ", ... (" + std::to_string(logs.size()) + " logs)";
  meta.source = "fit_surfaces from " + names;
  return meta;
}

// ---- data checks ------------------------------------------------------------------------------

std::string levelList(const std::vector<Level>& levels, const char* pattern) {
  std::string text;
  for (std::size_t k = 0; k < levels.size() && k < 6; ++k) text += (k ? ", " : "") + formatPrintf(pattern, levels[k].centre);
  if (levels.size() > 6) text += ", ...";
  return text;
}

// The logs some rows come from, for messages: "a.csv and b.csv", "a.csv, b.csv, c.csv and 5 more".
std::string logNames(const BenchDataset& data, const std::vector<bool>& used) {
  std::vector<std::string> names;
  for (std::size_t l = 0; l < data.sources.size(); ++l) {
    if (used[l]) names.push_back(data.sources[l]);
  }
  return nameList(names, 3);
}

std::string allLogNames(const BenchDataset& data) {
  return logNames(data, std::vector<bool>(data.sources.size(), true));
}

void requireSurfaceData(const BenchDataset& data) {
  const auto [vlo, vhi] = std::minmax_element(data.voltage_v.begin(), data.voltage_v.end());
  if (data.voltage_levels.size() < 2) {
    throw DataError("cannot fit a surface: one voltage level only (all " + std::to_string(data.rows()) + " rows of " +
                    allLogNames(data) + " have voltage_v near " +
                    formatPrintf("%.2f V", data.voltage_levels[0].centre) + ", " + formatPrintf("%.2f", *vlo) + " to " +
                    formatPrintf("%.2f V", *vhi) +
                    "); log sweeps at two or more supply voltages, or a battery discharge");
  }
  if (data.pwm_levels.size() < 3) {
    throw DataError("cannot fit a surface: " + std::to_string(data.pwm_levels.size()) + " PWM level" +
                    (data.pwm_levels.size() > 1 ? "s" : "") + " only (pwm_us of " + allLogNames(data) + ": " +
                    levelList(data.pwm_levels, "%.0f us") + "); log sweeps over at least 3 PWM values");
  }
}

// The column an output's samples come from, for messages.
const char* sampleColumn(Output output) {
  switch (output) {
    case Output::kThrust:
      return "thrust_n";
    case Output::kCurrent:
      return "current_a";
    case Output::kPower:
      return "power_w";
    case Output::kEfficiency:
      return "thrust_n / power_w";
    case Output::kRpm:
      return "rpm";
  }
  return "";
}

// How rows are grouped for cross-validation, resolved from FitOptions::grouping.
struct Grouping {
  FitGrouping kind = FitGrouping::kVoltageLevel;
  bool chosen_automatically = false;
  std::vector<int> group_of_row;
  std::vector<std::string> group_names;  // "the 11.06 V level", "the 1500 us level", a log's source
  std::string description;

  int groups() const { return static_cast<int>(group_names.size()); }
};

Grouping resolveGrouping(const BenchDataset& data, FitGrouping requested) {
  Grouping grouping;
  const int voltage_levels = static_cast<int>(data.voltage_levels.size());
  grouping.chosen_automatically = requested == FitGrouping::kAuto;
  // Voltage levels when holding one out leaves at least two to fit a voltage term.
  grouping.kind = requested != FitGrouping::kAuto ? requested
                  : voltage_levels >= 3          ? FitGrouping::kVoltageLevel
                                                 : FitGrouping::kPwmLevel;
  switch (grouping.kind) {
    case FitGrouping::kVoltageLevel:
      grouping.group_of_row = data.voltage_level;
      for (const Level& level : data.voltage_levels) {
        grouping.group_names.push_back(formatPrintf("the %.2f V level", level.centre));
      }
      grouping.description = "leave one voltage level out (" + std::to_string(grouping.groups()) + " levels, " +
                             formatPrintf("%.2f", data.voltage_levels.front().centre) + " to " +
                             formatPrintf("%.2f V", data.voltage_levels.back().centre) + ")";
      break;
    case FitGrouping::kPwmLevel:
      grouping.group_of_row = data.pwm_level;
      for (const Level& level : data.pwm_levels) {
        grouping.group_names.push_back(formatPrintf("the %.0f us level", level.centre));
      }
      grouping.description = "leave one PWM level out (" + std::to_string(grouping.groups()) + " levels, " +
                             formatPrintf("%.0f", data.pwm_levels.front().centre) + " to " +
                             formatPrintf("%.0f us", data.pwm_levels.back().centre) + ")";
      if (voltage_levels == 2) grouping.description += "; 2 voltage levels only, so the voltage degree is at most 1";
      break;
    default:
      grouping.group_of_row = data.log;
      grouping.group_names = data.sources;
      grouping.description = "leave one log out (" + std::to_string(grouping.groups()) + " logs)";
      break;
  }
  return grouping;
}

// ---- one surface --------------------------------------------------------------------------------

struct SurfaceResult {
  ResponseSurface surface;
  FitQuality quality;
  std::vector<CandidateScore> candidates;
};

// Distinct levels present in the rows of each group, to cap the degrees a fold can determine.
struct LevelPresence {
  std::vector<std::vector<int>> rows;  // [group][level]
  std::vector<int> total;              // [level]

  LevelPresence(int groups, int levels) : rows(groups, std::vector<int>(levels, 0)), total(levels, 0) {}
  void add(int group, int level) {
    ++rows[group][level];
    ++total[level];
  }
  int presentWithout(int group) const {
    int present = 0;
    for (std::size_t level = 0; level < total.size(); ++level) present += total[level] - rows[group][level] > 0;
    return present;
  }
  int present() const {
    return static_cast<int>(std::count_if(total.begin(), total.end(), [](int n) { return n > 0; }));
  }
  // The first level with rows outside `group` (-1: none).
  int firstWithout(int group) const {
    for (std::size_t level = 0; level < total.size(); ++level) {
      if (total[level] - rows[group][level] > 0) return static_cast<int>(level);
    }
    return -1;
  }
};

std::string groupingFlag(const Grouping& grouping) {
  const char* kind = grouping.kind == FitGrouping::kVoltageLevel ? "voltage"
                     : grouping.kind == FitGrouping::kPwmLevel   ? "pwm"
                                                                 : "log";
  return grouping.chosen_automatically ? std::string("--group-by auto (by ") + kind + ")"
                                       : std::string("--group-by ") + kind;
}

// Every fold must keep two voltage levels of the output's rows, or every candidate has voltage
// degree 0 and the model silently ignores voltage.
void requireVoltageLevelsPerFold(const BenchDataset& data, Output output, const Grouping& grouping,
                                 const LevelPresence& voltage_presence, const std::vector<long>& rows_per_group,
                                 const std::vector<bool>& logs_with_output, long points) {
  const std::string name = outputName(output);
  if (voltage_presence.present() < 2) {
    const auto level = std::find_if(voltage_presence.total.begin(), voltage_presence.total.end(),
                                    [](int rows) { return rows > 0; }) -
                       voltage_presence.total.begin();
    throw DataError("cannot fit " + name + ": all " + std::to_string(points) + " rows of " +
                    logNames(data, logs_with_output) + " with " + sampleColumn(output) + " are at one voltage level (" +
                    formatPrintf("%.2f V", data.voltage_levels[level].centre) +
                    "); log it at two or more voltages or leave it out with --without " + name);
  }
  for (int g = 0; g < grouping.groups(); ++g) {
    if (rows_per_group[g] == 0 || voltage_presence.presentWithout(g) >= 2) continue;
    const std::string advice = grouping.kind == FitGrouping::kPwmLevel ? "use --group-by voltage or log"
                               : data.voltage_levels.size() < 3        ? "use --group-by pwm or auto"
                                                                       : "use --group-by pwm";
    const int remaining = voltage_presence.firstWithout(g);
    const std::string leaves =
        remaining < 0 ? "leaves no rows in a training fold (without " + grouping.group_names[g] + ")"
                      : "leaves one voltage level in a training fold (without " + grouping.group_names[g] + " only " +
                            formatPrintf("%.2f V", data.voltage_levels[remaining].centre) + " remains)";
    throw DataError("cannot fit " + name + ": " + groupingFlag(grouping) + " " + leaves +
                    ", so cross-validation cannot score a voltage term: " + advice);
  }
}

SurfaceResult fitSurface(const BenchDataset& data, Output output, const Grouping& grouping,
                         const InputScaling& scaling, const FitOptions& options) {
  const std::vector<double>& y = data.output(output);
  const std::string name = outputName(output);
  const int groups = grouping.groups();
  // Rows of this output, gathered per group.
  std::vector<std::vector<double>> gx(groups), gv(groups), gy(groups);
  LevelPresence voltage_presence(groups, static_cast<int>(data.voltage_levels.size()));
  LevelPresence pwm_presence(groups, static_cast<int>(data.pwm_levels.size()));
  std::vector<bool> logs_with_output(data.sources.size(), false);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0.0;
  long points = 0;
  for (std::size_t row = 0; row < data.rows(); ++row) {
    if (std::isnan(y[row])) continue;
    const int g = grouping.group_of_row[row];
    gx[g].push_back((data.pwm_us[row] - scaling.pwm_center_us) / scaling.pwm_scale_us);
    gv[g].push_back((data.voltage_v[row] - scaling.voltage_center_v) / scaling.voltage_scale_v);
    gy[g].push_back(y[row]);
    voltage_presence.add(g, data.voltage_level[row]);
    pwm_presence.add(g, data.pwm_level[row]);
    logs_with_output[data.log[row]] = true;
    lo = std::min(lo, y[row]);
    hi = std::max(hi, y[row]);
    sum += y[row];
    ++points;
  }
  if (points < options.min_points) {
    throw DataError("cannot fit " + name + ": " + std::to_string(points) + " rows" +
                    (points > 0 ? " of " + logNames(data, logs_with_output) : std::string()) + " have " +
                    sampleColumn(output) + ", at least " + std::to_string(options.min_points) + " are needed");
  }
  if (hi == lo) {
    throw DataError("cannot fit " + name + ": column " + sampleColumn(output) + " is " + formatPrintf("%g", lo) + " " +
                    fileUnit(output) + " in all " + std::to_string(points) + " rows of " +
                    logNames(data, logs_with_output) + " (a sensor that was not connected?)" +
                    (output == Output::kThrust ? "" : "; leave it out with --without " + name));
  }
  std::vector<long> rows_per_group(groups);
  for (int g = 0; g < groups; ++g) rows_per_group[g] = static_cast<long>(gy[g].size());
  requireVoltageLevelsPerFold(data, output, grouping, voltage_presence, rows_per_group, logs_with_output, points);
  const double mean = sum / static_cast<double>(points);
  GroupedLeastSquares squares(groups, mean);
  for (int g = 0; g < groups; ++g) squares.add(g, gx[g].data(), gv[g].data(), gy[g].data(), gy[g].size());

  // Candidates: every degree pair the data determines in every fold.
  std::vector<CandidateScore> candidates;
  for (int dx = 1; dx <= options.max_pwm_degree; ++dx) {
    for (int dv = 0; dv <= options.max_voltage_degree; ++dv) {
      const std::vector<int> terms = GroupedLeastSquares::subBasis(dx, dv);
      CandidateScore score{dx, dv, static_cast<int>(terms.size()), kNaN};
      bool determined = true;
      for (int g = 0; g < groups && determined; ++g) {
        if (squares.rows(g) == 0) continue;
        determined = dv <= voltage_presence.presentWithout(g) - 1 && dx <= pwm_presence.presentWithout(g) - 1 &&
                     points - squares.rows(g) > static_cast<long>(terms.size());
      }
      if (determined) score.held_out_rmse = squares.heldOutRmse(terms).value_or(kNaN);
      candidates.push_back(score);
    }
  }
  double best = std::numeric_limits<double>::infinity();
  for (const CandidateScore& c : candidates) {
    if (std::isfinite(c.held_out_rmse)) best = std::min(best, c.held_out_rmse);
  }
  if (!std::isfinite(best)) {
    throw DataError("cannot fit " + name + ": no polynomial degree is determined with one group held out (" +
                    grouping.description + ")");
  }
  const CandidateScore* chosen = nullptr;
  for (const CandidateScore& c : candidates) {
    if (!(c.held_out_rmse <= best * (1.0 + options.parsimony))) continue;
    if (!chosen || c.terms < chosen->terms || (c.terms == chosen->terms && c.held_out_rmse < chosen->held_out_rmse)) {
      chosen = &c;
    }
  }
  const std::vector<int> terms = GroupedLeastSquares::subBasis(chosen->pwm_degree, chosen->voltage_degree);
  const std::optional<Eigen::VectorXd> beta = squares.solve(terms);
  if (!beta) throw DataError("cannot fit " + name + ": the normal equations are singular on all data");
  std::vector<PolynomialTerm> polynomial;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const auto [i, j] = GroupedLeastSquares::fullBasis()[terms[t]];
    polynomial.push_back({i, j, (*beta)(t)});
  }
  ResponseSurface surface(Polynomial2D(std::move(polynomial)), scaling);

  FitQuality quality;
  quality.pwm_degree = chosen->pwm_degree;
  quality.voltage_degree = chosen->voltage_degree;
  quality.held_out_rmse = chosen->held_out_rmse;
  quality.grouping = grouping.description;
  return {std::move(surface), quality, std::move(candidates)};
}

// R^2, RMSE and maximum error of the model's output against the samples.
void compare(const BenchDataset& data, const PropulsionModel& model, OutputFitReport* report) {
  const std::vector<double>& y = data.output(report->output);
  double sse = 0.0, sum = 0.0, sum2 = 0.0, worst = 0.0;
  int n = 0;
  for (std::size_t row = 0; row < data.rows(); ++row) {
    if (std::isnan(y[row])) continue;
    const double error = model.evaluateRaw(report->output, data.pwm_us[row], data.voltage_v[row]) - y[row];
    sse += error * error;
    worst = std::max(worst, std::abs(error));
    sum += y[row];
    sum2 += y[row] * y[row];
    ++n;
  }
  report->points = n;
  if (n == 0) return;
  const double sst = sum2 - sum * sum / n;
  report->r2 = sst > 0.0 ? 1.0 - sse / sst : kNaN;
  report->rmse = std::sqrt(sse / n);
  report->max_error = worst;
}

bool measured(const BenchDataset& data, Output output) {
  const std::vector<double>& y = data.output(output);
  return std::any_of(y.begin(), y.end(), [](double value) { return !std::isnan(value); });
}

}  // namespace

void FitOptions::validate() const {
  if (max_pwm_degree < 1 || max_pwm_degree > GroupedLeastSquares::kMaxPwmDegree) {
    throw ConfigError("max PWM degree " + std::to_string(max_pwm_degree) + " is outside 1..5");
  }
  if (max_voltage_degree < 0 || max_voltage_degree > GroupedLeastSquares::kMaxVoltageDegree) {
    throw ConfigError("max voltage degree " + std::to_string(max_voltage_degree) + " is outside 0..3");
  }
  if (!(parsimony >= 0.0)) throw ConfigError("parsimony must not be negative");
  if (min_points < 3) throw ConfigError("min points must be at least 3");
  if (without.count(Output::kThrust)) throw ConfigError("thrust cannot be left out: it is what the estimator is for");
  if (without.count(Output::kEfficiency)) {
    throw ConfigError("efficiency cannot be left out: it is derived from thrust and power at no cost");
  }
  levels.validate();
}

BenchFit fitBenchModel(const std::vector<BenchLog>& logs, const FitOptions& options) {
  options.validate();
  BenchDataset data = buildBenchDataset(logs, options.levels);
  requireSurfaceData(data);
  std::vector<std::string> notes = data.notes;
  const ModelMetadata metadata = resolveMetadata(logs, options, &notes);

  ModelDomain domain;
  std::tie(domain.pwm_min_us, domain.pwm_max_us) = [&] {
    const auto [lo, hi] = std::minmax_element(data.pwm_us.begin(), data.pwm_us.end());
    return std::make_pair(*lo, *hi);
  }();
  std::tie(domain.voltage_min_v, domain.voltage_max_v) = [&] {
    const auto [lo, hi] = std::minmax_element(data.voltage_v.begin(), data.voltage_v.end());
    return std::make_pair(*lo, *hi);
  }();
  domain.outside = options.outside;
  const InputScaling scaling{
      0.5 * (domain.pwm_min_us + domain.pwm_max_us), 0.5 * (domain.pwm_max_us - domain.pwm_min_us),
      0.5 * (domain.voltage_min_v + domain.voltage_max_v), 0.5 * (domain.voltage_max_v - domain.voltage_min_v)};

  const Grouping grouping = resolveGrouping(data, options.grouping);

  std::array<OutputDefinition, kOutputCount> definitions;
  std::array<OutputFitReport, kOutputCount> reports;
  auto fitted = [&](Output output) {
    const int o = static_cast<int>(output);
    SurfaceResult result = fitSurface(data, output, grouping, scaling, options);
    definitions[o].source = OutputSource::kSurface;
    definitions[o].surface = std::move(result.surface);
    definitions[o].fit = result.quality;
    reports[o].candidates = std::move(result.candidates);
  };
  auto absent = [&](Output output, const std::string& why) {
    definitions[static_cast<int>(output)].source = OutputSource::kNone;
    definitions[static_cast<int>(output)].note = why;
  };
  auto derived = [&](Output output, const std::string& why) {
    definitions[static_cast<int>(output)].source = OutputSource::kDerived;
    definitions[static_cast<int>(output)].note = why;
  };
  for (Output output : kAllOutputs) {
    definitions[static_cast<int>(output)].unit = fileUnit(output);
    reports[static_cast<int>(output)].output = output;
    reports[static_cast<int>(output)].unit = fileUnit(output);
  }

  fitted(Output::kThrust);
  const bool current_logged = measured(data, Output::kCurrent);
  const bool power_column =
      std::any_of(logs.begin(), logs.end(), [](const BenchLog& log) { return log.has(BenchColumn::kPower); });
  if (options.without.count(Output::kCurrent))
    absent(Output::kCurrent, "left out on request (--without current)");
  else if (current_logged)
    fitted(Output::kCurrent);
  else if (power_column && !options.without.count(Output::kPower))
    derived(Output::kCurrent, "the logs have no current column");
  else
    absent(Output::kCurrent, "the logs have no current column");

  if (options.without.count(Output::kPower)) {
    absent(Output::kPower, "left out on request (--without power)");
  } else if (power_column) {
    fitted(Output::kPower);
  } else if (definitions[static_cast<int>(Output::kCurrent)].source == OutputSource::kSurface) {
    derived(Output::kPower, "the logs have current but no power column");
  } else {
    absent(Output::kPower, "the logs have neither power nor current");
  }

  const bool power_modelled = definitions[static_cast<int>(Output::kPower)].source != OutputSource::kNone;
  if (options.efficiency_surface)
    fitted(Output::kEfficiency);
  else if (power_modelled)
    derived(Output::kEfficiency, "thrust / power, as the bench defines it");
  else
    absent(Output::kEfficiency, "no power to divide thrust by");

  if (options.without.count(Output::kRpm))
    absent(Output::kRpm, "left out on request (--without rpm)");
  else if (measured(data, Output::kRpm))
    fitted(Output::kRpm);
  else
    absent(Output::kRpm, "the logs have no rpm column");

  PropulsionModel model(metadata, domain, definitions);
  for (Output output : kAllOutputs) {
    OutputFitReport& report = reports[static_cast<int>(output)];
    report.source = model.output(output).source;
    if (report.source != OutputSource::kNone) compare(data, model, &report);
  }
  // FitQuality in the model says what the report says.
  std::array<OutputDefinition, kOutputCount> with_quality = definitions;
  for (Output output : kAllOutputs) {
    const int o = static_cast<int>(output);
    if (!with_quality[o].fit) continue;
    with_quality[o].fit->points = reports[o].points;
    with_quality[o].fit->r2 = reports[o].r2;
    with_quality[o].fit->rmse = reports[o].rmse;
    with_quality[o].fit->max_error = reports[o].max_error;
  }
  PropulsionModel final_model(metadata, domain, with_quality);
  std::string validation_error;
  try {
    validateModelOnGrid(final_model);
  } catch (const FieldError& e) {
    validation_error = e.what();
    // An output the model can do without: say how to have the rest.
    for (Output output : {Output::kCurrent, Output::kPower, Output::kRpm}) {
      if (e.field() == std::string("outputs.") + outputName(output)) {
        validation_error += std::string("; --without ") + outputName(output) + " writes the rest of the model";
      }
    }
  }
  return BenchFit{std::move(final_model), validation_error, std::move(data), grouping.kind, grouping.description,
                  reports, notes, options.parsimony};
}

}  // namespace fitting
}  // namespace propulsion_estimator
