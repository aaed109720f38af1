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
#include "propulsion_estimator/fitting/fit_grouping.h"
#include "propulsion_estimator/fitting/grouped_least_squares.h"
#include "propulsion_estimator/fitting/surface_candidates.h"
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

// A fall by more than this share of the output's range between grid neighbours is not physical.
constexpr double kMonotoneTolerance = 0.005;

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

// What the fits of one output need besides its rows: how rows are grouped and banded, where the
// surfaces are judged, and the options.
struct SurfaceContext {
  const Grouping& grouping;
  const std::vector<VoltageBand>& band_of_level;
  const ModelDomain& domain;
  const InputScaling& scaling;
  const FitOptions& options;
};

// The polyXY candidates, each with its held-out and band errors and whether it is physical.
std::vector<SurfaceCandidate> polynomialCandidates(const GroupedLeastSquares& cells, const SurfaceContext& context,
                                                   const LevelPresence& voltage_presence,
                                                   const LevelPresence& pwm_presence, long points, bool monotone,
                                                   double tolerance) {
  const int groups = context.grouping.groups();
  std::vector<int> group_of_cell(cells.groups()), band_of_cell(cells.groups());
  for (int c = 0; c < cells.groups(); ++c) {
    group_of_cell[c] = c / kVoltageBandCount;
    band_of_cell[c] = c % kVoltageBandCount;
  }
  const GroupedLeastSquares squares = cells.merged(group_of_cell, groups);
  const GroupedLeastSquares by_band = cells.merged(band_of_cell, kVoltageBandCount);
  // Voltage levels left when a band is held out, to say which candidates a band fold determines.
  std::array<int, kVoltageBandCount> levels_without_band{};
  for (std::size_t level = 0; level < voltage_presence.total.size(); ++level) {
    for (int b = 0; b < kVoltageBandCount; ++b) {
      levels_without_band[b] += voltage_presence.total[level] > 0 && static_cast<int>(context.band_of_level[level]) != b;
    }
  }
  std::vector<SurfaceCandidate> candidates;
  for (int dx = 1; dx <= context.options.max_pwm_degree; ++dx) {
    for (int dv = 0; dv <= context.options.max_voltage_degree; ++dv) {
      const std::vector<int> terms = GroupedLeastSquares::subBasis(dx, dv);
      SurfaceCandidate candidate;
      candidate.score = CandidateScore{dx, dv, static_cast<int>(terms.size()), kNaN, "polynomial", kNaN, kNaN, true};
      bool determined = true;
      for (int g = 0; g < groups && determined; ++g) {
        if (squares.rows(g) == 0) continue;
        determined = dv <= voltage_presence.presentWithout(g) - 1 && dx <= pwm_presence.presentWithout(g) - 1 &&
                     points - squares.rows(g) > static_cast<long>(terms.size());
      }
      if (determined) candidate.score.held_out_rmse = squares.heldOutRmse(terms).value_or(kNaN);
      for (VoltageBand b : {VoltageBand::kLow, VoltageBand::kHigh}) {
        const int i = static_cast<int>(b);
        if (dv > levels_without_band[i] - 1 || points - by_band.rows(i) <= static_cast<long>(terms.size())) continue;
        (b == VoltageBand::kLow ? candidate.score.low_band_rmse : candidate.score.high_band_rmse) =
            by_band.heldOutRmseOf(terms, i).value_or(kNaN);
      }
      if (const std::optional<Eigen::VectorXd> beta = squares.solve(terms)) {
        std::vector<PolynomialTerm> polynomial;
        for (std::size_t t = 0; t < terms.size(); ++t) {
          const auto [i, j] = GroupedLeastSquares::fullBasis()[terms[t]];
          polynomial.push_back({i, j, (*beta)(t)});
        }
        candidate.surface = ResponseSurface(Polynomial2D(std::move(polynomial)), context.scaling);
        candidate.score.physical = !monotone || isNonDecreasing(*candidate.surface, context.domain, tolerance);
      }
      candidates.push_back(std::move(candidate));
    }
  }
  return candidates;
}

SurfaceResult fitSurface(const BenchDataset& data, Output output, const SurfaceContext& context) {
  const std::vector<double>& y = data.output(output);
  const std::string name = outputName(output);
  const Grouping& grouping = context.grouping;
  const InputScaling& scaling = context.scaling;
  const int groups = grouping.groups();
  const int cells = groups * kVoltageBandCount;
  // Rows of this output, gathered per (group, band) cell.
  std::vector<std::vector<double>> gx(cells), gv(cells), gy(cells);
  FitRows rows;
  rows.groups = groups;
  for (auto* column : {&rows.pwm_us, &rows.voltage_v, &rows.y}) column->reserve(data.rows());
  rows.group.reserve(data.rows());
  rows.band.reserve(data.rows());
  LevelPresence voltage_presence(groups, static_cast<int>(data.voltage_levels.size()));
  LevelPresence pwm_presence(groups, static_cast<int>(data.pwm_levels.size()));
  std::vector<bool> logs_with_output(data.sources.size(), false);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0.0;
  long points = 0;
  for (std::size_t row = 0; row < data.rows(); ++row) {
    if (std::isnan(y[row])) continue;
    const int g = grouping.group_of_row[row];
    const VoltageBand band = context.band_of_level[data.voltage_level[row]];
    const int cell = g * kVoltageBandCount + static_cast<int>(band);
    gx[cell].push_back((data.pwm_us[row] - scaling.pwm_center_us) / scaling.pwm_scale_us);
    gv[cell].push_back((data.voltage_v[row] - scaling.voltage_center_v) / scaling.voltage_scale_v);
    gy[cell].push_back(y[row]);
    rows.pwm_us.push_back(data.pwm_us[row]);
    rows.voltage_v.push_back(data.voltage_v[row]);
    rows.y.push_back(y[row]);
    rows.group.push_back(g);
    rows.band.push_back(band);
    voltage_presence.add(g, data.voltage_level[row]);
    pwm_presence.add(g, data.pwm_level[row]);
    logs_with_output[data.log[row]] = true;
    lo = std::min(lo, y[row]);
    hi = std::max(hi, y[row]);
    sum += y[row];
    ++points;
  }
  if (points < context.options.min_points) {
    throw DataError("cannot fit " + name + ": " + std::to_string(points) + " rows" +
                    (points > 0 ? " of " + logNames(data, logs_with_output) : std::string()) + " have " +
                    sampleColumn(output) + ", at least " + std::to_string(context.options.min_points) + " are needed");
  }
  if (hi == lo) {
    throw DataError("cannot fit " + name + ": column " + sampleColumn(output) + " is " + formatPrintf("%g", lo) + " " +
                    fileUnit(output) + " in all " + std::to_string(points) + " rows of " +
                    logNames(data, logs_with_output) + " (a sensor that was not connected?)" +
                    (output == Output::kThrust ? "" : "; leave it out with --without " + name));
  }
  std::vector<long> rows_per_group(groups, 0);
  for (int c = 0; c < cells; ++c) rows_per_group[c / kVoltageBandCount] += static_cast<long>(gy[c].size());
  requireVoltageLevelsPerFold(data, output, grouping, voltage_presence, rows_per_group, logs_with_output, points);
  GroupedLeastSquares squares(cells, sum / static_cast<double>(points));
  for (int c = 0; c < cells; ++c) squares.add(c, gx[c].data(), gv[c].data(), gy[c].data(), gy[c].size());

  // Efficiency need not rise with PWM; every other output does, and a surface that does not is refused.
  const bool monotone = output != Output::kEfficiency;
  const double tolerance = kMonotoneTolerance * (hi - lo);
  std::vector<SurfaceCandidate> candidates =
      polynomialCandidates(squares, context, voltage_presence, pwm_presence, points, monotone, tolerance);
  for (SurfaceCandidate& c : driveCurveCandidates(rows)) candidates.push_back(std::move(c));
  const SurfaceCandidate* chosen = chooseCandidate(candidates, context.options.parsimony);
  if (!chosen) {
    const bool determined = std::any_of(candidates.begin(), candidates.end(), [](const SurfaceCandidate& c) {
      return c.surface && std::isfinite(c.score.held_out_rmse);
    });
    if (determined) {
      throw DataError("cannot fit " + name + ": no candidate surface rises with PWM and voltage over the bench's " +
                      "domain (does column " + sampleColumn(output) + " fall as PWM rises? a sensor read with the " +
                      "wrong sign)" + (output == Output::kThrust ? "" : "; leave it out with --without " + name));
    }
    throw DataError("cannot fit " + name + ": no candidate surface is determined with one group held out (" +
                    grouping.description + ")");
  }
  FitQuality quality;
  quality.basis = chosen->score.basis;
  quality.pwm_degree = chosen->score.pwm_degree;
  quality.voltage_degree = chosen->score.voltage_degree;
  quality.held_out_rmse = chosen->score.held_out_rmse;
  quality.grouping = grouping.description;
  if (std::isfinite(chosen->score.low_band_rmse)) quality.low_band_rmse = chosen->score.low_band_rmse;
  if (std::isfinite(chosen->score.high_band_rmse)) quality.high_band_rmse = chosen->score.high_band_rmse;
  std::vector<CandidateScore> scores;
  for (const SurfaceCandidate& c : candidates) scores.push_back(c.score);
  if (chosen->drive_fit && rows.size() > 0) {
    return {ResponseSurface(refitOnAllRows(rows, *chosen->drive_fit)), quality, std::move(scores)};
  }
  return {*chosen->surface, quality, std::move(scores)};
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
  // Per PWM level the voltages logged there: a discharge never logs a high PWM on a low battery.
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<CoveredLevel> covered(data.pwm_levels.size(), CoveredLevel{0.0, inf, -inf});
  for (std::size_t row = 0; row < data.rows(); ++row) {
    CoveredLevel& level = covered[data.pwm_level[row]];
    level.voltage_min_v = std::min(level.voltage_min_v, data.voltage_v[row]);
    level.voltage_max_v = std::max(level.voltage_max_v, data.voltage_v[row]);
  }
  for (std::size_t k = 0; k < covered.size(); ++k) {
    covered[k].pwm_us = std::clamp(data.pwm_levels[k].centre, domain.pwm_min_us, domain.pwm_max_us);
  }
  domain.covered = std::move(covered);
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
  OutputPlan(const BenchDataset& data, const SurfaceContext& context) : data_(data), context_(context) {
    for (Output output : kAllOutputs) {
      definitions_[index(output)].unit = fileUnit(output);
      reports_[index(output)].output = output;
      reports_[index(output)].unit = fileUnit(output);
    }
  }

  void fitted(Output output) {
    SurfaceResult result = fitSurface(data_, output, context_);
    const double r2 = explained(result.surface, data_.output(output));
    if (output != Output::kThrust && r2 < kPoorFitR2) {
      const std::string name = outputName(output);
      // The advice names a --map the reader takes: the bench quantity, not the output's name.
      const std::string advice =
          output == Output::kRpm ? " (an electrical speed, or dropouts?): map the rotor's speed with --map rpm=<column>, "
                                   "or log it with the motor's pole count set in the stand's software"
          : output == Output::kEfficiency
              ? " (a noisy power sensor?): keep --efficiency derived, or map another power column with "
                "--map power_w=<column>"
              : std::string(" (a noisy or misread sensor?): map another column with --map ") + sampleColumn(output) +
                    "=<column>";
      const std::string why =
          formatPrintf("its best surface explains only R^2 %.2f", r2) + " of column " + sampleColumn(output) + advice;
      absent(output, "left out: " + why);
      reports_[index(output)].candidates = std::move(result.candidates);
      reports_[index(output)].left_out = name + " left out: " + why;
      return;
    }
    definitions_[index(output)].source = OutputSource::kSurface;
    definitions_[index(output)].surface = std::move(result.surface);
    definitions_[index(output)].fit = result.quality;
    reports_[index(output)].candidates = std::move(result.candidates);
  }
  void derived(Output output, const std::string& why) { set(output, OutputSource::kDerived, why); }
  void absent(Output output, const std::string& why) { set(output, OutputSource::kNone, why); }
  OutputSource source(Output output) const { return definitions_[index(output)].source; }
  bool without(Output output) const { return context_.options.without.count(output) > 0; }

  const std::array<OutputDefinition, kOutputCount>& definitions() const { return definitions_; }
  std::array<OutputFitReport, kOutputCount>& reports() { return reports_; }

 private:
  static int index(Output output) { return static_cast<int>(output); }
  void set(Output output, OutputSource source, const std::string& why) {
    definitions_[index(output)].source = source;
    definitions_[index(output)].note = why;
  }

  // R^2 of a surface against the rows that have the output (an even subsample of at most 100000
  // rows: enough to tell a column that fits from one that does not).
  double explained(const ResponseSurface& surface, const std::vector<double>& y) const {
    const std::size_t stride = std::max<std::size_t>(1, data_.rows() / 100000);
    double sse = 0.0, sum = 0.0, sum2 = 0.0;
    long n = 0;
    for (std::size_t row = 0; row < data_.rows(); row += stride) {
      if (std::isnan(y[row])) continue;
      const double error = surface.evaluate(data_.pwm_us[row], data_.voltage_v[row]) - y[row];
      sse += error * error;
      sum += y[row];
      sum2 += y[row] * y[row];
      ++n;
    }
    const double sst = sum2 - sum * sum / static_cast<double>(n);
    return sst > 0.0 ? 1.0 - sse / sst : 1.0;
  }

  const BenchDataset& data_;
  const SurfaceContext& context_;
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
  VoltageBands bands;
  const std::vector<VoltageBand> band_of_level = voltageBandOfLevels(data, &bands);

  const SurfaceContext context{grouping, band_of_level, domain, scaling, options};
  OutputPlan plan(data, context);
  plan.fitted(Output::kThrust);
  planCurrentAndPower(logs, data, &plan);
  planEfficiencyAndRpm(data, options.efficiency_surface, &plan);

  std::array<OutputFitReport, kOutputCount> reports = plan.reports();
  for (const OutputFitReport& report : reports) {
    if (!report.left_out.empty()) notes.push_back(report.left_out);
  }
  PropulsionModel model = modelWithQuality(metadata, domain, data, plan.definitions(), &reports);
  std::string validation_error = gridCheckError(model);
  return BenchFit{std::move(model), std::move(validation_error), std::move(data), grouping.kind,
                  grouping.description, reports, notes, options.parsimony, bands};
}

}  // namespace fitting
}  // namespace propulsion_estimator
