#include "propulsion_estimator/fitting/comparison_report.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "propulsion_estimator/fitting/bench_dataset.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace fitting {
namespace {

void writeSamples(std::ofstream& out, const std::string& label, const std::vector<ComparisonSample>& samples) {
  for (const ComparisonSample& s : samples) {
    out << label << "," << formatCsvNumber(s.voltage_v) << "," << formatCsvNumber(s.pwm_us) << ","
        << formatCsvNumber(s.thrust_g) << "," << formatCsvNumber(s.current_a) << "," << formatCsvNumber(s.power_w)
        << "," << formatCsvNumber(s.efficiency_g_per_w) << "," << formatCsvNumber(s.rpm) << "\n";
  }
}

}  // namespace

std::string comparisonTables(const std::vector<ModelComparison>& models, const ComparisonOptions& options) {
  std::ostringstream md;
  md << "| combination | ESC | motor | propeller | at (V) | max thrust (g) | max current (A) | max power (W) | max rpm "
        "| "
        "efficiency at max power (g/W) | peak efficiency (g/W) at PWM (us) | max motor temperature (deg C) |\n";
  md << "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const ModelComparison& m : models) {
    md << "| " << m.label << " | " << m.metadata.esc << " | " << m.metadata.motor << " | " << m.metadata.propeller
       << " | " << formatPrintf("%.2f", m.voltage_v, "n/a") << " | " << formatPrintf("%.1f", m.max_thrust_g, "n/a")
       << " | " << formatPrintf("%.2f", m.max_current_a, "n/a") << " | " << formatPrintf("%.1f", m.max_power_w, "n/a")
       << " | " << formatPrintf("%.0f", m.max_rpm, "n/a") << " | "
       << formatPrintf("%.2f", m.efficiency_at_max_power_g_per_w, "n/a") << " | "
       << formatPrintf("%.2f", m.peak_efficiency_g_per_w, "n/a") << " at "
       << formatPrintf("%.0f", m.peak_efficiency_pwm_us, "n/a") << " | "
       << (m.max_motor_temp_c ? formatPrintf("%.1f", *m.max_motor_temp_c, "n/a") : "not logged") << " |\n";
  }
  bool first_note = true;
  for (const ModelComparison& m : models) {
    for (const std::string& note : m.notes) {
      md << (first_note ? "\n" : "") << "- " << m.label << ": " << note << "\n";
      first_note = false;
    }
  }
  if (!options.hover) return md.str();
  const HoverOptions& h = *options.hover;
  md << "\nHover of a " << formatPrintf("%.4g", h.vehicle_mass_kg, "n/a") << " kg vehicle on " << h.motors
     << " motors (" << formatPrintf("%.1f", h.thrustPerMotorN() / kNewtonPerGramForce, "n/a") << " g each), " << h.cells
     << "S " << formatPrintf("%.0f", h.capacity_mah, "n/a") << " mAh; operating point at the mid-discharge "
     << formatPrintf("%.2f", h.midVoltage(), "n/a") << " V:\n\n";
  md << "| combination | PWM (us) | current per motor (A) | power per motor (W) | efficiency (g/W) | total current (A) "
        "| "
        "hover endurance (min) | notes |\n";
  md << "|---|---:|---:|---:|---:|---:|---:|---|\n";
  for (const ModelComparison& m : models) {
    md << "| " << m.label << " | ";
    if (m.hover) {
      md << formatPrintf("%.0f", m.hover->pwm_us, "n/a") << " | " << formatPrintf("%.2f", m.hover->current_a, "n/a")
         << " | " << formatPrintf("%.1f", m.hover->power_w, "n/a") << " | "
         << formatPrintf("%.2f", m.hover->efficiency_g_per_w, "n/a") << " | "
         << formatPrintf("%.1f", h.motors * m.hover->current_a, "n/a") << " | ";
    } else {
      md << "n/a | n/a | n/a | n/a | n/a | ";
    }
    md << (m.endurance_min ? formatPrintf("%.1f", *m.endurance_min, "n/a") : "n/a") << " | ";
    for (std::size_t k = 0; k < m.hover_notes.size(); ++k) md << (k ? "; " : "") << m.hover_notes[k];
    md << " |\n";
  }
  return md.str();
}

void writeComparisonReportData(const std::vector<ModelComparison>& models, const ComparisonOptions& options,
                               const std::string& directory) {
  const std::string header = "model,voltage_v,pwm_us,thrust_g,current_a,power_w,efficiency_g_per_w,rpm\n";
  std::ofstream curves = openReportFile(directory, "compare_curves.csv");
  std::ofstream points = openReportFile(directory, "compare_points.csv");
  curves << header;
  points << header;
  std::ofstream hover = openReportFile(directory, "compare_hover.csv");
  hover << "model,thrust_per_motor_g,voltage_v,pwm_us,current_a,power_w,efficiency_g_per_w,endurance_min\n";
  std::ofstream discharge = openReportFile(directory, "compare_discharge.csv");
  discharge << "model,time_min,voltage_v,total_current_a,pwm_us\n";
  for (const ModelComparison& m : models) {
    writeSamples(curves, m.label, m.curve);
    writeSamples(points, m.label, m.logged_near);
    if (!options.hover) continue;
    hover << m.label << "," << formatCsvNumber(options.hover->thrustPerMotorN() / kNewtonPerGramForce) << ",";
    if (m.hover) {
      hover << formatCsvNumber(m.hover->voltage_v) << "," << formatCsvNumber(m.hover->pwm_us) << ","
            << formatCsvNumber(m.hover->current_a) << "," << formatCsvNumber(m.hover->power_w) << ","
            << formatCsvNumber(m.hover->efficiency_g_per_w) << ",";
    } else {
      hover << ",,,,,";
    }
    hover << (m.endurance_min ? formatCsvNumber(*m.endurance_min) : "") << "\n";
    for (const DischargeStep& step : m.discharge) {
      discharge << m.label << "," << formatCsvNumber(step.time_s / 60.0) << "," << formatCsvNumber(step.voltage_v) << ","
                << formatCsvNumber(step.total_current_a) << "," << formatCsvNumber(step.pwm_us) << "\n";
    }
  }
  for (std::ofstream* file : {&curves, &points, &hover, &discharge}) {
    file->flush();
    if (!*file) throw InputError(directory + ": cannot write the report's data");
  }
}

std::vector<std::string> comparisonReportFigures(const ComparisonOptions& options) {
  std::vector<std::string> figures = {"compare_curves.png"};
  if (options.hover) figures.push_back("compare_endurance.png");
  return figures;
}

std::string comparisonReportMarkdown(const std::vector<ModelComparison>& models, const ComparisonOptions& options) {
  std::ostringstream md;
  md << "# Comparison of " << models.size() << " ESC-motor-propeller combinations\n\n";
  md << "Maxima over each model's PWM domain at "
     << (options.voltage_v ? formatPrintf("%.2f V", *options.voltage_v, "n/a")
                           : std::string("the top of each model's voltage domain"))
     << ", as thesis chapter 7 tabulates them. Peak efficiency is taken where the motor draws at least "
     << formatPrintf("%.0f", 100.0 * kEfficiencyMinPowerShare, "n/a")
     << "% of its maximum power (near idle thrust / power is a ratio of two near-zero numbers).\n\n";
  md << comparisonTables(models, options) << "\n";
  if (options.hover) {
    const HoverOptions& h = *options.hover;
    md << "Endurance integrates the hover current of all motors while the battery voltage falls linearly with the "
          "charge drawn, from "
       << formatPrintf("%.2f", h.fullVoltage(), "n/a") << " V (" << formatPrintf("%.2f", h.cell_full_v, "n/a")
       << " V per cell) to " << formatPrintf("%.2f", h.cutoffVoltage(), "n/a") << " V ("
       << formatPrintf("%.2f", h.cell_cutoff_v, "n/a") << " V per cell) over "
       << formatPrintf("%.0f", 100.0 * h.usable_fraction, "n/a") << "% of "
       << formatPrintf("%.0f", h.capacity_mah, "n/a") << " mAh, in " << h.steps
       << " steps, the hover PWM solved anew at each voltage. It counts propulsion current only (no avionics), "
          "ignores the battery's internal resistance beyond that linear fall, and uses each model as its domain and "
          "outside policy allow.\n\n";
  }
  md << "## Figures\n\n";
  for (const std::string& figure : comparisonReportFigures(options)) md << "![" << figure << "](" << figure << ")\n\n";
  return md.str();
}

}  // namespace fitting
}  // namespace propulsion_estimator
