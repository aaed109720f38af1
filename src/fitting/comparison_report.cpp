#include "propulsion_estimator/fitting/comparison_report.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "propulsion_estimator/fitting/bench_dataset.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/units.h"

namespace propulsion_estimator {
namespace {

std::string number(double value, const char* pattern) {
  return std::isnan(value) ? "n/a" : formatPrintf(pattern, value);
}

std::string cell(double value) { return std::isnan(value) ? "" : number(value, "%.7g"); }

void writeSamples(std::ofstream& out, const std::string& label, const std::vector<ComparisonSample>& samples) {
  for (const ComparisonSample& s : samples) {
    out << label << "," << cell(s.voltage_v) << "," << cell(s.pwm_us) << "," << cell(s.thrust_g) << ","
        << cell(s.current_a) << "," << cell(s.power_w) << "," << cell(s.efficiency_g_per_w) << "," << cell(s.rpm)
        << "\n";
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
       << " | " << number(m.voltage_v, "%.2f") << " | " << number(m.max_thrust_g, "%.1f") << " | "
       << number(m.max_current_a, "%.2f") << " | " << number(m.max_power_w, "%.1f") << " | "
       << number(m.max_rpm, "%.0f") << " | " << number(m.efficiency_at_max_power_g_per_w, "%.2f") << " | "
       << number(m.peak_efficiency_g_per_w, "%.2f") << " at " << number(m.peak_efficiency_pwm_us, "%.0f") << " | "
       << (m.max_motor_temp_c ? number(*m.max_motor_temp_c, "%.1f") : "not logged") << " |\n";
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
  md << "\nHover of a " << number(h.vehicle_mass_kg, "%.4g") << " kg vehicle on " << h.motors << " motors ("
     << number(h.thrustPerMotorN() / kNewtonPerGramForce, "%.1f") << " g each), " << h.cells << "S "
     << number(h.capacity_mah, "%.0f") << " mAh; operating point at the mid-discharge "
     << number(h.midVoltage(), "%.2f") << " V:\n\n";
  md << "| combination | PWM (us) | current per motor (A) | power per motor (W) | efficiency (g/W) | total current (A) "
        "| "
        "hover endurance (min) | notes |\n";
  md << "|---|---:|---:|---:|---:|---:|---:|---|\n";
  for (const ModelComparison& m : models) {
    md << "| " << m.label << " | ";
    if (m.hover) {
      md << number(m.hover->pwm_us, "%.0f") << " | " << number(m.hover->current_a, "%.2f") << " | "
         << number(m.hover->power_w, "%.1f") << " | " << number(m.hover->efficiency_g_per_w, "%.2f") << " | "
         << number(h.motors * m.hover->current_a, "%.1f") << " | ";
    } else {
      md << "n/a | n/a | n/a | n/a | n/a | ";
    }
    md << (m.endurance_min ? number(*m.endurance_min, "%.1f") : "n/a") << " | ";
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
    hover << m.label << "," << cell(options.hover->thrustPerMotorN() / kNewtonPerGramForce) << ",";
    if (m.hover) {
      hover << cell(m.hover->voltage_v) << "," << cell(m.hover->pwm_us) << "," << cell(m.hover->current_a) << ","
            << cell(m.hover->power_w) << "," << cell(m.hover->efficiency_g_per_w) << ",";
    } else {
      hover << ",,,,,";
    }
    hover << (m.endurance_min ? cell(*m.endurance_min) : "") << "\n";
    for (const DischargeStep& step : m.discharge) {
      discharge << m.label << "," << cell(step.time_min) << "," << cell(step.voltage_v) << ","
                << cell(step.total_current_a) << "," << cell(step.pwm_us) << "\n";
    }
  }
  for (std::ofstream* file : {&curves, &points, &hover, &discharge}) {
    file->flush();
    if (!*file) throw ConfigError(directory + ": cannot write the report's data");
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
     << (options.voltage_v ? number(*options.voltage_v, "%.2f V")
                           : std::string("the top of each model's voltage domain"))
     << ", as thesis chapter 7 tabulates them. Peak efficiency is taken where the motor draws at least "
     << number(100.0 * kEfficiencyMinPowerShare, "%.0f")
     << "% of its maximum power (near idle thrust / power is a ratio of two near-zero numbers).\n\n";
  md << comparisonTables(models, options) << "\n";
  if (options.hover) {
    const HoverOptions& h = *options.hover;
    md << "Endurance integrates the hover current of all motors while the battery voltage falls linearly with the "
          "charge drawn, from "
       << number(h.fullVoltage(), "%.2f") << " V (" << number(h.cell_full_v, "%.2f") << " V per cell) to "
       << number(h.cutoffVoltage(), "%.2f") << " V (" << number(h.cell_cutoff_v, "%.2f") << " V per cell) over "
       << number(100.0 * h.usable_fraction, "%.0f") << "% of " << number(h.capacity_mah, "%.0f") << " mAh, in "
       << h.steps
       << " steps, the hover PWM solved anew at each voltage. It counts propulsion current only (no avionics), "
          "ignores the battery's internal resistance beyond that linear fall, and uses each model as its domain and "
          "outside policy allow.\n\n";
  }
  md << "## Figures\n\n";
  for (const std::string& figure : comparisonReportFigures(options)) md << "![" << figure << "](" << figure << ")\n\n";
  return md.str();
}

}  // namespace propulsion_estimator
