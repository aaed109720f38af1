#pragma once

#include <string>
#include <vector>

#include "propulsion_estimator/gap/diagnosis.h"

namespace propulsion_estimator {
namespace gap {

/// report.yaml: the diagnosis for machines (gap, where, motors, effects, selected, heldout).
std::string gapReportYaml(const Diagnosis& diagnosis);

/// gap_samples.csv in `directory`: one row per block (truth, both views, corrected, signals),
/// which `plot_bench_report.py gap DIR` draws. Throws InputError when it cannot be written.
void writeGapReportData(const Diagnosis& diagnosis, const std::string& directory);

/// The figures the plot script draws, in report order.
const std::vector<std::string>& gapReportFigures();

/// report.md: the gap, where it lies, the motor balance, every candidate effect, the selection
/// and how far the gap shrinks on held-out flights, with the figures. `command` is the command
/// line that produced it.
std::string gapReportMarkdown(const Diagnosis& diagnosis, const PropulsionModel& model, const std::string& command);

}  // namespace gap
}  // namespace propulsion_estimator
