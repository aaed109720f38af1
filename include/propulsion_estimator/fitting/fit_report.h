#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/fitting/surface_fit.h"

namespace propulsion_estimator {
namespace fitting {

/// The numbers behind fit_surfaces' report, as CSV files in one directory, which
/// scripts/plot_bench_report.py turns into figures:
///   fit_outputs.csv         output, unit, source (surface/derived/none)
///   fit_points.csv          every sample: log, line, levels, inputs, measured, fitted, residual
///   fit_curves_pwm.csv      fitted output against PWM at each voltage level (thesis 4.1 sections)
///   fit_curves_voltage.csv  fitted output against voltage at up to 6 PWM levels (thesis 4.2)
///   fit_surface_grid.csv    the surfaces on a 61 x 31 grid over the domain (contour maps)
/// Throws InputError naming `directory` when a file cannot be written.
void writeFitReportData(const BenchFit& fit, const std::string& directory);

/// The figures the plot script draws from those files, in report order.
const std::vector<std::string>& fitReportFigures();

/// The Markdown report: data, levels and notes, bench conditions, the quality of each output,
/// every candidate's held-out error, the validation verdict and the figures. `model_path` is where
/// the model was written (empty when it was not, because validation failed).
std::string fitReportMarkdown(const BenchFit& fit, const std::string& model_path);

}  // namespace fitting
}  // namespace propulsion_estimator
