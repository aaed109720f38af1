#include "propulsion_estimator/fitting/surface_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>

#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/field_error.h"
#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/fitting/bench_metadata.h"
#include "propulsion_estimator/fitting/grouped_least_squares.h"
#include "propulsion_estimator/model/model_validation.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/model/polynomial_2d.h"

namespace propulsion_estimator {
namespace fitting {
namespace {

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

// The box the bench covered, with the policy outside it.
ModelDomain measuredDomain(const BenchDataset& data, OutsideDomain outside) {
  ModelDomain domain;
  const auto [pwm_lo, pwm_hi] = std::minmax_element(data.pwm_us.begin(), data.pwm_us.end());
  const auto [voltage_lo, voltage_hi] = std::minmax_element(data.voltage_v.begin(), data.voltage_v.end());
  domain.pwm_min_us = *pwm_lo;
  domain.pwm_max_us = *pwm_hi;
  domain.voltage_min_v = *voltage_lo;
  domain.voltage_max_v = *voltage_hi;
  domain.outside = outside;
  return domain;
}

// Inputs centred and scaled to [-1, 1] over the domain.
InputScaling domainScaling(const ModelDomain& domain) {
  return {0.5 * (domain.pwm_min_us + domain.pwm_max_us), 0.5 * (domain.pwm_max_us - domain.pwm_min_us),
          0.5 * (domain.voltage_min_v + domain.voltage_max_v), 0.5 * (domain.voltage_max_v - domain.voltage_min_v)};
}

// The outputs' definitions and reports as the fit decides them, output by output: fitted as a
// surface, derived from others, or absent, each with why.
class OutputPlan {
 public:
  OutputPlan(const BenchDataset& data, const Grouping& grouping, const InputScaling& scaling,
             const FitOptions& options)
      : data_(data), grouping_(grouping), scaling_(scaling), options_(options) {
    for (Output output : kAllOutputs) {
      definitions_[index(output)].unit = fileUnit(output);
      reports_[index(output)].output = output;
      reports_[index(output)].unit = fileUnit(output);
    }
  }

  void fitted(Output output) {
    SurfaceResult result = fitSurface(data_, output, grouping_, scaling_, options_);
    definitions_[index(output)].source = OutputSource::kSurface;
    definitions_[index(output)].surface = std::move(result.surface);
    definitions_[index(output)].fit = result.quality;
    reports_[index(output)].candidates = std::move(result.candidates);
  }
  void derived(Output output, const std::string& why) { set(output, OutputSource::kDerived, why); }
  void absent(Output output, const std::string& why) { set(output, OutputSource::kNone, why); }
  OutputSource source(Output output) const { return definitions_[index(output)].source; }
  bool without(Output output) const { return options_.without.count(output) > 0; }

  const std::array<OutputDefinition, kOutputCount>& definitions() const { return definitions_; }
  std::array<OutputFitReport, kOutputCount>& reports() { return reports_; }

 private:
  static int index(Output output) { return static_cast<int>(output); }
  void set(Output output, OutputSource source, const std::string& why) {
    definitions_[index(output)].source = source;
    definitions_[index(output)].note = why;
  }

  const BenchDataset& data_;
  const Grouping& grouping_;
  const InputScaling& scaling_;
  const FitOptions& options_;
  std::array<OutputDefinition, kOutputCount> definitions_;
  std::array<OutputFitReport, kOutputCount> reports_;
};

// Current and power: each fitted where logged, derived from the other where it can be, else absent.
void planCurrentAndPower(const std::vector<BenchLog>& logs, const BenchDataset& data, OutputPlan* plan) {
  const bool power_column =
      std::any_of(logs.begin(), logs.end(), [](const BenchLog& log) { return log.has(BenchColumn::kPower); });
  if (plan->without(Output::kCurrent))
    plan->absent(Output::kCurrent, "left out on request (--without current)");
  else if (measured(data, Output::kCurrent))
    plan->fitted(Output::kCurrent);
  else if (power_column && !plan->without(Output::kPower))
    plan->derived(Output::kCurrent, "the logs have no current column");
  else
    plan->absent(Output::kCurrent, "the logs have no current column");

  if (plan->without(Output::kPower))
    plan->absent(Output::kPower, "left out on request (--without power)");
  else if (power_column)
    plan->fitted(Output::kPower);
  else if (plan->source(Output::kCurrent) == OutputSource::kSurface)
    plan->derived(Output::kPower, "the logs have current but no power column");
  else
    plan->absent(Output::kPower, "the logs have neither power nor current");
}

// Efficiency derived as thrust / power unless its own surface is asked for; rpm fitted where logged.
void planEfficiencyAndRpm(const BenchDataset& data, bool efficiency_surface, OutputPlan* plan) {
  if (efficiency_surface)
    plan->fitted(Output::kEfficiency);
  else if (plan->source(Output::kPower) != OutputSource::kNone)
    plan->derived(Output::kEfficiency, "thrust / power, as the bench defines it");
  else
    plan->absent(Output::kEfficiency, "no power to divide thrust by");

  if (plan->without(Output::kRpm))
    plan->absent(Output::kRpm, "left out on request (--without rpm)");
  else if (measured(data, Output::kRpm))
    plan->fitted(Output::kRpm);
  else
    plan->absent(Output::kRpm, "the logs have no rpm column");
}

// The model with each surface's FitQuality saying what the report says (R^2, RMSE and maximum
// error against all rows).
PropulsionModel modelWithQuality(const ModelMetadata& metadata, const ModelDomain& domain, const BenchDataset& data,
                                 std::array<OutputDefinition, kOutputCount> definitions,
                                 std::array<OutputFitReport, kOutputCount>* reports) {
  const PropulsionModel model(metadata, domain, definitions);
  for (Output output : kAllOutputs) {
    const int o = static_cast<int>(output);
    OutputFitReport& report = (*reports)[o];
    report.source = model.output(output).source;
    if (report.source != OutputSource::kNone) compare(data, model, &report);
    if (!definitions[o].fit) continue;
    definitions[o].fit->points = report.points;
    definitions[o].fit->r2 = report.r2;
    definitions[o].fit->rmse = report.rmse;
    definitions[o].fit->max_error = report.max_error;
  }
  return PropulsionModel(metadata, domain, std::move(definitions));
}

// Empty when the model passes the loader's grid check, else why not, and for an output the model
// can do without, how to have the rest.
std::string gridCheckError(const PropulsionModel& model) {
  try {
    validateModelOnGrid(model);
  } catch (const FieldError& e) {
    std::string error = e.what();
    for (Output output : {Output::kCurrent, Output::kPower, Output::kRpm}) {
      if (e.field() == std::string("outputs.") + outputName(output)) {
        error += std::string("; --without ") + outputName(output) + " writes the rest of the model";
      }
    }
    return error;
  }
  return "";
}

}  // namespace

BenchFit fitBenchModel(const std::vector<BenchLog>& logs, const FitOptions& options) {
  options.validate();
  BenchDataset data = buildBenchDataset(logs, options.levels);
  requireSurfaceData(data);
  std::vector<std::string> notes = data.notes;
  const ModelMetadata metadata = resolveBenchMetadata(logs, options, &notes);
  const ModelDomain domain = measuredDomain(data, options.outside);
  const InputScaling scaling = domainScaling(domain);
  const Grouping grouping = resolveGrouping(data, options.grouping);

  OutputPlan plan(data, grouping, scaling, options);
  plan.fitted(Output::kThrust);
  planCurrentAndPower(logs, data, &plan);
  planEfficiencyAndRpm(data, options.efficiency_surface, &plan);

  std::array<OutputFitReport, kOutputCount> reports = plan.reports();
  PropulsionModel model = modelWithQuality(metadata, domain, data, plan.definitions(), &reports);
  std::string validation_error = gridCheckError(model);
  return BenchFit{std::move(model), std::move(validation_error), std::move(data), grouping.kind,
                  grouping.description, reports, notes, options.parsimony};
}

}  // namespace fitting
}  // namespace propulsion_estimator
