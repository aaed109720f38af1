#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/fitting/model_comparison.h"

namespace propulsion_estimator {
namespace fitting {

/// The tables of compare_models in Markdown: thesis chapter 7's maxima per combination and,
/// when hover options were given, the hover operating point and endurance.
std::string comparisonTables(const std::vector<ModelComparison>& models, const ComparisonOptions& options);

/// The numbers behind the figures, as CSV files for scripts/plot_bench_report.py:
///   compare_curves.csv     each model against PWM at its comparison voltage
///   compare_points.csv     log rows near that voltage
///   compare_hover.csv      hover point and endurance per model (empty values where none)
///   compare_discharge.csv  hover current during the battery discharge
/// Throws InputError naming `directory` when a file cannot be written.
void writeComparisonReportData(const std::vector<ModelComparison>& models, const ComparisonOptions& options,
                               const std::string& directory);

/// The figures the plot script draws from them (the endurance figure only with hover options).
std::vector<std::string> comparisonReportFigures(const ComparisonOptions& options);

/// The whole report: the tables, how hover and endurance were computed, and the figures.
std::string comparisonReportMarkdown(const std::vector<ModelComparison>& models, const ComparisonOptions& options);

}  // namespace fitting
}  // namespace propulsion_estimator
