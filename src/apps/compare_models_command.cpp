#include "compare_models_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <set>

#include "bench_log_options.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/cells_in_series.h"
#include "propulsion_estimator/fitting/comparison_report.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/fitting/model_comparison.h"
#include "propulsion_estimator/model/model_yaml.h"
#include "propulsion_estimator/common/yaml_map.h"
#include "report_plotter.h"
#include "tool_command.h"

namespace propulsion_estimator {
namespace {

struct Arguments {
  std::vector<std::string> models;
  std::optional<double> voltage_v;
  std::optional<double> mass_kg;
  std::optional<int> cells;
  std::optional<double> capacity_mah;
  fitting::HoverOptions hover;
  std::string report;
  ReportPlotter plotter;
};

// "dir/g1.yaml=a.csv,b/" -> model path and log arguments.
std::pair<std::string, std::vector<std::string>> splitModelArgument(const std::string& argument) {
  const std::size_t equals = argument.find('=');
  if (equals == std::string::npos) return {argument, {}};
  std::vector<std::string> logs;
  std::size_t start = equals + 1;
  while (start <= argument.size()) {
    std::size_t comma = argument.find(',', start);
    if (comma == std::string::npos) comma = argument.size();
    if (comma > start) logs.push_back(argument.substr(start, comma - start));
    start = comma + 1;
  }
  return {argument.substr(0, equals), logs};
}

int compare(Arguments args, const BenchReadOptions& read_options) {
  if (args.models.size() < 2) throw UsageError("give two or more models to compare");
  if (!args.report.empty()) args.plotter.check();
  fitting::ComparisonOptions options;
  options.voltage_v = args.voltage_v;
  if (args.mass_kg || args.cells || args.capacity_mah) {
    if (!args.mass_kg || !args.cells || !args.capacity_mah) {
      throw UsageError("hover needs --mass-kg, --cells and --capacity-mah together");
    }
    args.hover.vehicle_mass_kg = *args.mass_kg;
    args.hover.cells = *args.cells;
    args.hover.capacity_mah = *args.capacity_mah;
    options.hover = args.hover;
  }
  std::vector<fitting::ModelComparison> comparisons;
  std::set<std::string> labels;
  for (const std::string& argument : args.models) {
    const auto [path, log_arguments] = splitModelArgument(argument);
    const PropulsionModel model = loadModelFile(path);
    std::vector<BenchLog> logs;
    if (!log_arguments.empty()) logs = readBenchLogs(log_arguments, read_options);
    std::string label = std::filesystem::path(path).stem().string();
    if (!labels.insert(label).second) label = path;
    comparisons.push_back(fitting::compareModel(label, model, logs, options));
  }
  std::printf("%s", fitting::comparisonTables(comparisons, options).c_str());
  if (!args.report.empty()) {
    std::filesystem::create_directories(args.report);
    fitting::writeComparisonReportData(comparisons, options, args.report);
    args.plotter.plot("compare", args.report);
    const std::string path = args.report + "/compare_report.md";
    writeTextFile(path, fitting::comparisonReportMarkdown(comparisons, options));
    std::printf("report: %s\n", path.c_str());
  }
  return 0;
}

}  // namespace

int runCompareModels(int argc, char** argv) {
  CLI::App app{
      "Compares ESC-motor-propeller combinations from their model files (thesis chapter 7): maxima at one "
      "voltage, and with a vehicle and battery the hover point and hover endurance of each."};
  Arguments args;
  BenchLogOptions log_options;
  app.add_option("models", args.models,
                 "Model files, each optionally with its bench logs for motor temperature and data points: "
                 "MODEL.yaml=LOG[,LOG|DIR...]")
      ->required();
  app.add_option("--voltage", args.voltage_v, "Voltage of the maxima and curves (default: top of each model's domain)")
      ->check(positiveNumber());
  app.add_option("--mass-kg", args.mass_kg, "Vehicle take-off mass for hover (kg)")->check(positiveNumber());
  app.add_option("--motors", args.hover.motors, "Number of motors")->check(wholeNumberIn(1, 16))->capture_default_str();
  app.add_option("--cells", args.cells, "LiPo cells in series")->check(wholeNumberIn(kMinCellsInSeries, kMaxCellsInSeries));
  app.add_option("--capacity-mah", args.capacity_mah, "Battery capacity (mAh)")->check(positiveNumber());
  app.add_option("--usable-fraction", args.hover.usable_fraction, "Share of the capacity used down to the cutoff")
      ->check(numberIn(0.01, 1.0))
      ->capture_default_str();
  app.add_option("--cell-full-v", args.hover.cell_full_v, "Cell voltage of a full battery under hover load")
      ->check(positiveNumber())
      ->capture_default_str();
  app.add_option("--cell-cutoff-v", args.hover.cell_cutoff_v, "Cell voltage at which the flight ends")
      ->check(positiveNumber())
      ->capture_default_str();
  app.add_option("--report", args.report, "Directory for the report (Markdown, CSV data, PNG figures)")
      ->check(folderToWrite());
  log_options.addTo(app);
  args.plotter.addTo(app);
  return runToolCommand("compare_models", app, argc, argv, [&] { return compare(args, log_options.readOptions()); });
}

}  // namespace propulsion_estimator
