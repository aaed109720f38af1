#include "propulsion_estimator/fitting/bench_dataset.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace fitting {
namespace {

double median(std::vector<double> values) {
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + mid));
}

// A log built in code (a simulator, a test) can break what the readers guarantee.
void requireShape(const BenchLog& log) {
  if (log.rows() == 0) throw DataError(log.source + ": the log has no rows");
  for (BenchColumn required : {BenchColumn::kPwm, BenchColumn::kVoltage, BenchColumn::kThrust}) {
    if (!log.has(required)) {
      throw DataError(log.source + ": column " + benchColumnName(required) +
                      " is missing (required: pwm_us, voltage_v, thrust_n)");
    }
  }
  for (int c = 0; c < kBenchColumnCount; ++c) {
    const auto column = static_cast<BenchColumn>(c);
    if (log.has(column) && log.column(column).size() != log.rows()) {
      throw DataError(log.source + ": column " + benchColumnName(column) + " has " +
                      std::to_string(log.column(column).size()) + " values for " + std::to_string(log.rows()) +
                      " rows");
    }
  }
}

void requireFinite(const BenchLog& log, BenchColumn column) {
  const std::vector<double>& values = log.column(column);
  for (std::size_t row = 0; row < values.size(); ++row) {
    if (!std::isfinite(values[row])) {
      throw DataError(log.source + ":" + std::to_string(log.line_numbers[row]) + ": " + benchColumnName(column) + ": " +
                      formatPrintf("%g", values[row]) + " is not a finite number");
    }
  }
}

// Thrust over power of a propeller on a stand, g/W, from micro rotors at full throttle to large
// slow ones: a log far outside was written in other units (grams under thrust_n, newtons under
// thrust_g, milliwatts or kilowatts), and a model fitted on it would be off a hundredfold.
constexpr double kLowestEfficiencyGPerW = 0.5;
constexpr double kHighestEfficiencyGPerW = 40.0;

// `efficiency_g_per_w`: the log's rows as the dataset holds them (NaN below its power share).
void requirePlausibleEfficiency(const BenchLog& log, const double* efficiency_g_per_w, std::size_t rows) {
  std::vector<double> efficiency;
  for (std::size_t r = 0; r < rows; ++r) {
    if (std::isfinite(efficiency_g_per_w[r])) efficiency.push_back(std::abs(efficiency_g_per_w[r]));
  }
  if (efficiency.empty()) return;
  const double typical = median(efficiency);
  if (typical >= kLowestEfficiencyGPerW && typical <= kHighestEfficiencyGPerW) return;
  throw DataError(log.source + ": thrust over power is " + formatPrintf("%.3g", typical) +
                  " g/W (the median), where propellers give " + formatPrintf("%g", kLowestEfficiencyGPerW) + "-" +
                  formatPrintf("%g", kHighestEfficiencyGPerW) +
                  " g/W: thrust or power logged in other units (grams under thrust_n, newtons under thrust_g, mW or kW)?");
}

// Levels of sorted keys: consecutive keys closer than `gap` join one level.
std::vector<int> clusterSorted(const std::vector<std::pair<double, int>>& keyed, double gap, int* count) {
  std::vector<int> level(keyed.size());
  int current = -1;
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    if (k == 0 || keyed[k].first - keyed[k - 1].first >= gap) ++current;
    level[k] = current;
  }
  *count = current + 1;
  return level;
}

void assignVoltageLevels(const std::vector<BenchLog>& logs, const LevelOptions& options, BenchDataset* data) {
  // Steady logs: one level per cluster of medians. Others: rows binned by voltage.
  std::vector<std::pair<double, int>> steady;  // (median, log)
  std::vector<bool> is_steady(logs.size(), false);
  std::vector<double> log_median(logs.size());
  for (std::size_t l = 0; l < logs.size(); ++l) {
    const std::vector<double>& v = logs[l].column(BenchColumn::kVoltage);
    log_median[l] = median(v);
    std::vector<double> deviation(v.size());
    for (std::size_t r = 0; r < v.size(); ++r) deviation[r] = std::abs(v[r] - log_median[l]);
    if (median(deviation) <= options.steady_voltage_mad_v) {
      is_steady[l] = true;
      steady.emplace_back(log_median[l], static_cast<int>(l));
    }
  }
  std::sort(steady.begin(), steady.end());
  int steady_levels = 0;
  const std::vector<int> steady_level = clusterSorted(steady, options.same_level_v, &steady_levels);

  // Level keys: steady clusters first (negative keys), bins by index (floor(v / width)).
  std::map<long, double> centre_sum;
  std::map<long, int> count;
  std::vector<long> row_key(data->rows());
  std::vector<long> log_key(logs.size(), 0);
  for (std::size_t k = 0; k < steady.size(); ++k) log_key[steady[k].second] = -1 - steady_level[k];
  for (std::size_t row = 0; row < data->rows(); ++row) {
    const int l = data->log[row];
    const double v = data->voltage_v[row];
    row_key[row] = is_steady[l] ? log_key[l] : static_cast<long>(std::floor(v / options.voltage_bin_v));
    centre_sum[row_key[row]] +=
        is_steady[l] ? log_median[l] : (std::floor(v / options.voltage_bin_v) + 0.5) * options.voltage_bin_v;
    ++count[row_key[row]];
  }
  // A steady level whose centre falls in an occupied bin is that bin's level.
  std::map<long, long> merged;
  for (const auto& [key, n] : count) {
    if (key >= 0) continue;
    const long bin = static_cast<long>(std::floor(centre_sum[key] / n / options.voltage_bin_v));
    if (count.count(bin)) merged[key] = bin;
  }
  std::vector<std::pair<double, long>> levels;  // (centre, key) of the surviving keys
  for (const auto& [key, n] : count) {
    if (merged.count(key)) continue;
    double sum = centre_sum[key];
    int rows = n;
    for (const auto& [from, to] : merged) {
      if (to == key) {
        sum += centre_sum[from];
        rows += count[from];
      }
    }
    levels.emplace_back(sum / rows, key);
  }
  std::sort(levels.begin(), levels.end());
  std::map<long, int> index;
  for (std::size_t k = 0; k < levels.size(); ++k) index[levels[k].second] = static_cast<int>(k);
  for (const auto& [from, to] : merged) index[from] = index[to];
  data->voltage_levels.assign(levels.size(), Level{});
  data->voltage_level.resize(data->rows());
  for (std::size_t row = 0; row < data->rows(); ++row) {
    const int level = index[row_key[row]];
    data->voltage_level[row] = level;
    ++data->voltage_levels[level].rows;
  }
  for (std::size_t k = 0; k < levels.size(); ++k) data->voltage_levels[k].centre = levels[k].first;

  // Supply sag within steady logs, for the report.
  for (std::size_t l = 0; l < logs.size(); ++l) {
    if (!is_steady[l]) {
      data->notes.push_back(logs[l].source + ": voltage varies (" +
                            formatPrintf("%.2f", *std::min_element(logs[l].column(BenchColumn::kVoltage).begin(),
                                                             logs[l].column(BenchColumn::kVoltage).end())) +
                            " to " +
                            formatPrintf("%.2f V", *std::max_element(logs[l].column(BenchColumn::kVoltage).begin(),
                                                               logs[l].column(BenchColumn::kVoltage).end())) +
                            "): its rows are binned by voltage in " + formatPrintf("%.2g V", options.voltage_bin_v) +
                            " bins");
      continue;
    }
    const std::vector<double>& v = logs[l].column(BenchColumn::kVoltage);
    int sagged = 0;
    std::size_t worst = 0;
    for (std::size_t r = 0; r < v.size(); ++r) {
      if (std::abs(v[r] - log_median[l]) > kSagNoteV) {
        ++sagged;
        if (std::abs(v[r] - log_median[l]) > std::abs(v[worst] - log_median[l])) worst = r;
      }
    }
    if (sagged == 0) continue;
    std::string note = logs[l].source + ": " + std::to_string(sagged) + " row" + (sagged > 1 ? "s" : "") +
                       " more than " + formatPrintf("%.1f V", kSagNoteV) + " off the sweep's " +
                       formatPrintf("%.2f V", log_median[l]) + " (down to " + formatPrintf("%.2f V", v[worst]) + " at " +
                       formatPrintf("%.0f us", logs[l].column(BenchColumn::kPwm)[worst]);
    if (logs[l].has(BenchColumn::kCurrent)) note += formatPrintf(", %.2f A", logs[l].column(BenchColumn::kCurrent)[worst]);
    note += "): the supply sagged; these rows are fitted at their measured voltage";
    data->notes.push_back(note);
  }
}

void assignPwmLevels(const LevelOptions& options, BenchDataset* data) {
  std::map<long, int> distinct;
  for (double x : data->pwm_us) ++distinct[std::lround(x)];
  data->pwm_level.resize(data->rows());
  if (static_cast<int>(distinct.size()) <= options.max_pwm_levels) {
    std::map<long, int> index;
    for (const auto& [value, n] : distinct) {
      index[value] = static_cast<int>(data->pwm_levels.size());
      data->pwm_levels.push_back({static_cast<double>(value), n});
    }
    for (std::size_t row = 0; row < data->rows(); ++row) data->pwm_level[row] = index[std::lround(data->pwm_us[row])];
    return;
  }
  const auto [lo, hi] = std::minmax_element(data->pwm_us.begin(), data->pwm_us.end());
  const double width = (*hi - *lo) / options.max_pwm_levels;
  std::vector<double> sum(options.max_pwm_levels, 0.0);
  std::vector<int> bin(data->rows());
  std::vector<int> rows(options.max_pwm_levels, 0);
  for (std::size_t row = 0; row < data->rows(); ++row) {
    bin[row] = std::min(options.max_pwm_levels - 1, static_cast<int>((data->pwm_us[row] - *lo) / width));
    sum[bin[row]] += data->pwm_us[row];
    ++rows[bin[row]];
  }
  std::vector<int> index(options.max_pwm_levels, -1);
  for (int b = 0; b < options.max_pwm_levels; ++b) {
    if (rows[b] == 0) continue;
    index[b] = static_cast<int>(data->pwm_levels.size());
    data->pwm_levels.push_back({sum[b] / rows[b], rows[b]});
  }
  for (std::size_t row = 0; row < data->rows(); ++row) data->pwm_level[row] = index[bin[row]];
}

}  // namespace

void LevelOptions::validate() const {
  if (!(steady_voltage_mad_v > 0.0)) {
    throw ConfigError("--steady-voltage-mad: " + formatPrintf("%g", steady_voltage_mad_v) + " V is not positive");
  }
  if (!(voltage_bin_v > 0.0)) {
    throw ConfigError("--voltage-bin: " + formatPrintf("%g", voltage_bin_v) + " V is not positive");
  }
  if (!(same_level_v > 0.0)) throw ConfigError("same-level voltage tolerance must be positive");
  if (max_pwm_levels < 3) throw ConfigError("max PWM levels must be at least 3");
}

BenchDataset buildBenchDataset(const std::vector<BenchLog>& logs, const LevelOptions& options) {
  options.validate();
  if (logs.empty()) throw ConfigError("no bench logs given");
  BenchDataset data;
  const int thrust = static_cast<int>(Output::kThrust), current = static_cast<int>(Output::kCurrent),
            power = static_cast<int>(Output::kPower), efficiency = static_cast<int>(Output::kEfficiency),
            rpm = static_cast<int>(Output::kRpm);
  for (std::size_t l = 0; l < logs.size(); ++l) {
    const BenchLog& log = logs[l];
    requireShape(log);
    for (int c = 0; c < kBenchColumnCount; ++c) {
      if (log.has(static_cast<BenchColumn>(c))) requireFinite(log, static_cast<BenchColumn>(c));
    }
    for (const std::string& note : log.notes) data.notes.push_back(log.source + ": " + note);
    data.sources.push_back(log.source);
    const std::size_t n = log.rows();
    const auto& x = log.column(BenchColumn::kPwm);
    const auto& v = log.column(BenchColumn::kVoltage);
    const auto& t = log.column(BenchColumn::kThrust);
    const bool has_current = log.has(BenchColumn::kCurrent), has_power = log.has(BenchColumn::kPower);
    if (has_current && !has_power) {
      data.notes.push_back(log.source + ": power taken as voltage x current (the log has no power column)");
    }
    std::vector<double> log_power(n, kNaN);
    for (std::size_t r = 0; r < n; ++r) {
      if (has_power)
        log_power[r] = log.column(BenchColumn::kPower)[r];
      else if (has_current)
        log_power[r] = v[r] * log.column(BenchColumn::kCurrent)[r];
    }
    const double peak_power = (has_power || has_current) ? *std::max_element(log_power.begin(), log_power.end()) : 0.0;
    for (std::size_t r = 0; r < n; ++r) {
      data.log.push_back(static_cast<int>(l));
      data.line.push_back(log.line_numbers[r]);
      data.pwm_us.push_back(x[r]);
      data.voltage_v.push_back(v[r]);
      const double thrust_g = t[r] / kNewtonPerGramForce;
      data.values[thrust].push_back(thrust_g);
      data.values[current].push_back(has_current ? log.column(BenchColumn::kCurrent)[r] : kNaN);
      data.values[power].push_back(log_power[r]);
      const bool efficient_enough = peak_power > 0.0 && log_power[r] >= kEfficiencyMinPowerShare * peak_power;
      data.values[efficiency].push_back(efficient_enough ? thrust_g / log_power[r] : kNaN);
      data.values[rpm].push_back(log.has(BenchColumn::kRpm) ? log.column(BenchColumn::kRpm)[r] : kNaN);
    }
    requirePlausibleEfficiency(log, data.values[efficiency].data() + data.values[efficiency].size() - n, n);
  }
  assignVoltageLevels(logs, options, &data);
  assignPwmLevels(options, &data);
  return data;
}

}  // namespace fitting
}  // namespace propulsion_estimator
