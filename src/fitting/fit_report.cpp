#include "propulsion_estimator/fitting/fit_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/not_a_number.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/text_file.h"

namespace propulsion_estimator {
namespace fitting {
namespace {

constexpr int kCurvePoints = 101;
constexpr int kGridPwm = 61;
constexpr int kGridVoltage = 31;
constexpr std::size_t kMaxVoltageSections = 6;
// Samples drawn per output: a million-row fit would make figures no one can read (and slow to draw).
constexpr long kMaxPlottedPoints = 20000;

long plotStride(long samples) { return (samples + kMaxPlottedPoints - 1) / kMaxPlottedPoints; }

std::string baseName(const std::string& path) { return path.substr(path.find_last_of('/') + 1); }

const char* sourceName(OutputSource source) {
  switch (source) {
    case OutputSource::kSurface:
      return "surface";
    case OutputSource::kDerived:
      return "derived";
    case OutputSource::kNone:
      return "none";
  }
  return "?";
}

double lerp(double lo, double hi, int k, int n) { return lo + (hi - lo) * k / (n - 1); }

// The PWM levels the voltage sections show: all of them, or evenly spread ones.
std::vector<int> sectionPwmLevels(const BenchDataset& data) {
  std::vector<int> levels;
  const std::size_t n = data.pwm_levels.size();
  const std::size_t shown = std::min(n, kMaxVoltageSections);
  for (std::size_t k = 0; k < shown; ++k) {
    levels.push_back(static_cast<int>(shown == 1 ? 0 : k * (n - 1) / (shown - 1)));
  }
  return levels;
}

// An output where the bench covered the inputs; NaN (an empty cell, a gap in a figure) elsewhere.
double coveredValue(const PropulsionModel& model, Output output, double pwm_us, double voltage_v) {
  return model.domain().contains(pwm_us, voltage_v) ? model.evaluateRaw(output, pwm_us, voltage_v) : kNaN;
}

std::vector<Output> modelled(const PropulsionModel& model) {
  std::vector<Output> outputs;
  for (Output output : kAllOutputs) {
    if (model.output(output).source != OutputSource::kNone) outputs.push_back(output);
  }
  return outputs;
}

}  // namespace

const std::vector<std::string>& fitReportFigures() {
  static const std::vector<std::string> figures = {"fit_sections_pwm.png", "fit_sections_voltage.png",
                                                   "fit_residuals.png", "fit_surfaces.png"};
  return figures;
}

void writeFitReportData(const BenchFit& fit, const std::string& directory) {
  const PropulsionModel& model = fit.model;
  const BenchDataset& data = fit.data;
  const ModelDomain& domain = model.domain();
  const std::vector<Output> outputs = modelled(model);

  std::ofstream kinds = openReportFile(directory, "fit_outputs.csv");
  kinds << "output,unit,source\n";
  for (Output output : kAllOutputs) {
    kinds << outputName(output) << "," << model.output(output).unit << "," << sourceName(model.output(output).source)
          << "\n";
  }

  std::ofstream points = openReportFile(directory, "fit_points.csv");
  // measured_at_pwm_level: the sample moved along the surface from its PWM to its PWM level's,
  // so that the voltage sections show the noise, not the width of a PWM bin.
  points << "output,log,line,voltage_level_v,pwm_level_us,pwm_us,voltage_v,off_level,measured,fitted,residual,"
            "measured_at_pwm_level\n";
  for (Output output : outputs) {
    const std::vector<double>& y = data.output(output);
    const long stride = plotStride(fit.outputs[static_cast<int>(output)].points);
    long seen = 0;
    for (std::size_t row = 0; row < data.rows(); ++row) {
      if (std::isnan(y[row]) || seen++ % stride != 0) continue;
      const double level_v = data.voltage_levels[data.voltage_level[row]].centre;
      const double pwm_level = data.pwm_levels[data.pwm_level[row]].centre;
      const double fitted = model.evaluateRaw(output, data.pwm_us[row], data.voltage_v[row]);
      const double at_level = y[row] + model.evaluateRaw(output, pwm_level, data.voltage_v[row]) - fitted;
      points << outputName(output) << "," << baseName(data.sources[data.log[row]]) << "," << data.line[row] << ","
             << formatCsvNumber(level_v) << "," << formatCsvNumber(pwm_level) << ","
             << formatCsvNumber(data.pwm_us[row]) << "," << formatCsvNumber(data.voltage_v[row]) << ","
             << (std::abs(data.voltage_v[row] - level_v) > kSagNoteV ? 1 : 0) << "," << formatCsvNumber(y[row]) << ","
             << formatCsvNumber(fitted) << "," << formatCsvNumber(fitted - y[row]) << "," << formatCsvNumber(at_level)
             << "\n";
    }
  }

  std::ofstream pwm_curves = openReportFile(directory, "fit_curves_pwm.csv");
  pwm_curves << "output,voltage_v,pwm_us,fitted\n";
  for (Output output : outputs) {
    for (const Level& level : data.voltage_levels) {
      for (int k = 0; k < kCurvePoints; ++k) {
        const double x = lerp(domain.pwm_min_us, domain.pwm_max_us, k, kCurvePoints);
        pwm_curves << outputName(output) << "," << formatCsvNumber(level.centre) << "," << formatCsvNumber(x) << ","
                   << formatCsvNumber(coveredValue(model, output, x, level.centre)) << "\n";
      }
    }
  }

  std::ofstream voltage_curves = openReportFile(directory, "fit_curves_voltage.csv");
  voltage_curves << "output,pwm_us,voltage_v,fitted\n";
  const std::vector<int> sections = sectionPwmLevels(data);
  for (Output output : outputs) {
    for (int level : sections) {
      const double x = data.pwm_levels[level].centre;
      for (int k = 0; k < kCurvePoints; ++k) {
        const double v = lerp(domain.voltage_min_v, domain.voltage_max_v, k, kCurvePoints);
        voltage_curves << outputName(output) << "," << formatCsvNumber(x) << "," << formatCsvNumber(v) << ","
                       << formatCsvNumber(coveredValue(model, output, x, v)) << "\n";
      }
    }
  }

  std::ofstream grid = openReportFile(directory, "fit_surface_grid.csv");
  grid << "output,pwm_us,voltage_v,value\n";
  for (Output output : outputs) {
    for (int b = 0; b < kGridVoltage; ++b) {
      const double v = lerp(domain.voltage_min_v, domain.voltage_max_v, b, kGridVoltage);
      for (int a = 0; a < kGridPwm; ++a) {
        const double x = lerp(domain.pwm_min_us, domain.pwm_max_us, a, kGridPwm);
        grid << outputName(output) << "," << formatCsvNumber(x) << "," << formatCsvNumber(v) << ","
             << formatCsvNumber(coveredValue(model, output, x, v)) << "\n";
      }
    }
  }
  for (std::ofstream* file : {&kinds, &points, &pwm_curves, &voltage_curves, &grid}) {
    file->flush();
    if (!*file) throw InputError(directory + ": cannot write the report's data");
  }
}

namespace {

void writeVerdict(const BenchFit& fit, const std::string& model_path, std::ostringstream& md) {
  const ModelMetadata& meta = fit.model.metadata();
  md << "# Response surfaces: " << meta.esc << " / " << meta.motor << " / " << meta.propeller << "\n\n";
  if (fit.validation_error.empty()) {
    md << "Model written to `" << model_path << "`; it passes the loader's checks (`loadModelFile`).\n\n";
  } else {
    md << "**The fitted model fails the loader's check on its domain grid and was not written:** "
       << fit.validation_error
       << ". The data do not determine the surface there; see the figures, log more points where it fails, or "
          "narrow the data to the range that will be flown.\n\n";
  }
}

void writeLogTable(const BenchDataset& data, std::ostringstream& md) {
  md << "| log | rows | PWM (us) | voltage (V) |\n|---|---:|---|---|\n";
  for (std::size_t l = 0; l < data.sources.size(); ++l) {
    double xlo = 1e300, xhi = -1e300, vlo = 1e300, vhi = -1e300;
    int rows = 0;
    for (std::size_t row = 0; row < data.rows(); ++row) {
      if (data.log[row] != static_cast<int>(l)) continue;
      xlo = std::min(xlo, data.pwm_us[row]);
      xhi = std::max(xhi, data.pwm_us[row]);
      vlo = std::min(vlo, data.voltage_v[row]);
      vhi = std::max(vhi, data.voltage_v[row]);
      ++rows;
    }
    md << "| " << baseName(data.sources[l]) << " | " << rows << " | " << formatPrintf("%.0f", xlo, "") << "-"
       << formatPrintf("%.0f", xhi, "") << " | " << formatPrintf("%.2f", vlo, "") << "-"
       << formatPrintf("%.2f", vhi, "") << " |\n";
  }
}

// The box and, inside it, the voltages the bench covered at each PWM level.
void writeDomain(const BenchDataset& data, const ModelDomain& domain, std::ostringstream& md) {
  const auto [vlo, vhi] = std::minmax_element(data.voltage_v.begin(), data.voltage_v.end());
  md << "\n- Domain: PWM " << formatPrintf("%.0f", domain.pwm_min_us, "") << " to "
     << formatPrintf("%.0f", domain.pwm_max_us, "") << " us, voltage " << formatPrintf("%.2f", domain.voltage_min_v, "")
     << " to " << formatPrintf("%.2f", domain.voltage_max_v, "") << " V at the rows' measured voltage ("
     << formatPrintf("%.2f", *vlo, "") << " V was logged at "
     << formatPrintf("%.0f", data.pwm_us[vlo - data.voltage_v.begin()], "") << " us, " << formatPrintf("%.2f", *vhi, "")
     << " V at " << formatPrintf("%.0f", data.pwm_us[vhi - data.voltage_v.begin()], "")
     << " us). Within that box the model's domain is only what the bench covered, the voltage range logged at "
        "each PWM level (interpolated between levels); outside it the model will "
     << outsideDomainName(domain.outside) << ", and the estimator flags the sample.\n\n";
  md << "| PWM level (us) | covered voltage (V) |\n|---:|---|\n";
  for (const CoveredLevel& level : domain.covered) {
    md << "| " << formatPrintf("%.0f", level.pwm_us, "") << " | " << formatPrintf("%.2f", level.voltage_min_v, "")
       << " to " << formatPrintf("%.2f", level.voltage_max_v, "") << " |\n";
  }
  md << "\n";
}

void writeDataSection(const BenchFit& fit, std::ostringstream& md) {
  const ModelMetadata& meta = fit.model.metadata();
  const BenchDataset& data = fit.data;
  md << "## Data\n\n";
  writeLogTable(data, md);
  writeDomain(data, fit.model.domain(), md);
  if (meta.hasBenchAir()) {
    md << "- Bench: air " << formatPrintf("%.1f", *meta.bench_air_temperature_c, "") << " deg C, "
       << formatPrintf("%.0f", *meta.bench_air_pressure_pa, "") << " Pa (density "
       << formatPrintf("%.4f", meta.benchAirDensity(), "") << " kg/m^3), " << supplyKindName(meta.supply)
       << " supply.\n";
  } else {
    md << "- Bench: air unknown, " << supplyKindName(meta.supply) << " supply.\n";
  }
  md << "- Voltage levels (" << data.voltage_levels.size() << "):";
  for (std::size_t k = 0; k < data.voltage_levels.size(); ++k) {
    md << (k ? ", " : " ") << formatPrintf("%.2f", data.voltage_levels[k].centre, "") << " V ("
       << data.voltage_levels[k].rows << " rows)";
  }
  md << ".\n- PWM levels: " << data.pwm_levels.size() << ", "
     << formatPrintf("%.0f", data.pwm_levels.front().centre, "") << " to "
     << formatPrintf("%.0f", data.pwm_levels.back().centre, "") << " us.\n";
  md << "- Cross-validation: " << fit.grouping_description
     << ". Whole groups are held out, never random rows. Candidates are the MATLAB polyXY degrees up to (5, 3) and "
        "drive curves y = sum c_k u^k, u = max(0, PWM - x0) / 1000 us * V, of degree 1 to 3 with c_k >= 0 (they "
        "rise with PWM and voltage everywhere), with the ESC's full-throttle end point x1 where the bench logged a "
        "plateau (u stops rising at x1; taken when rows at two PWM values or more lie above it and it cuts the "
        "squared error by a third with F >= 20); each is also fitted above the lowest voltage band and judged on "
        "it, and below the highest. A polynomial that falls with PWM or voltage anywhere in the covered domain is not "
        "chosen; of the rest, the one with the fewest terms within "
     << formatPrintf("%g", 100.0 * fit.parsimony, "")
     << "% of the lowest worst score (the largest of its determined held-out, low-band and high-band RMSE) is "
        "chosen.\n\n";
  if (!fit.notes.empty()) {
    md << "### Notes\n\n";
    for (const std::string& note : fit.notes) md << "- " << note << "\n";
    md << "\n";
  }
}

// The ESC's full-throttle end point of a drive curve, us; infinite for any other surface.
double fullThrottleUs(const OutputDefinition& def) {
  return def.surface && def.surface->driveCurve() ? def.surface->driveCurve()->pwmFullUs()
                                                  : DriveCurve::kNoFullThrottle;
}

std::string degrees(const OutputDefinition& def) {
  const FitQuality& fit = *def.fit;
  if (fit.basis != "drive_curve") {
    return "(" + std::to_string(fit.pwm_degree) + ", " + std::to_string(fit.voltage_degree) + ")";
  }
  const double x1 = fullThrottleUs(def);
  return "drive curve, degree " + std::to_string(fit.pwm_degree) +
         (std::isfinite(x1) ? formatPrintf(", full throttle at %.0f us", x1, "") : "");
}

std::string optionalNumber(const std::optional<double>& value) {
  return value ? formatPrintf("%.4g", *value, "") : "-";
}

void writeQualitySection(const BenchFit& fit, std::ostringstream& md) {
  const PropulsionModel& model = fit.model;
  md << "## Fit quality\n\n";
  md << "| output | unit | model | degrees (x, v) | points | R^2 | RMSE | max error | held-out RMSE | low-band RMSE | "
        "high-band RMSE |\n";
  md << "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (Output output : kAllOutputs) {
    const OutputDefinition& def = model.output(output);
    const OutputFitReport& report = fit.outputs[static_cast<int>(output)];
    md << "| " << outputName(output) << " | " << def.unit << " | " << sourceName(def.source);
    if (def.source == OutputSource::kNone) {
      md << ": " << def.note << " | | | | | | | | |\n";
      continue;
    }
    if (def.source == OutputSource::kDerived) md << " (" << def.note << ")";
    md << " | " << (def.fit ? degrees(def) : "") << " | " << report.points << " | "
       << formatPrintf("%.5f", report.r2, "") << " | " << formatPrintf("%.4g", report.rmse, "") << " | "
       << formatPrintf("%.4g", report.max_error, "") << " | "
       << (def.fit ? formatPrintf("%.4g", def.fit->held_out_rmse, "") : "") << " | "
       << (def.fit ? optionalNumber(def.fit->low_band_rmse) : "") << " | "
       << (def.fit ? optionalNumber(def.fit->high_band_rmse) : "") << " |\n";
  }
  md << "\nDerived outputs are compared with the bench's own ratio where the row drew at least "
     << formatPrintf("%.0f", 100.0 * kEfficiencyMinPowerShare, "") << "% of its log's peak power.";
  const long stride = plotStride(fit.outputs[static_cast<int>(Output::kThrust)].points);
  if (stride > 1) md << " The figures show every " << stride << "th sample.";
  md << "\n\n";
}

// How far below the bench's lowest voltage the thrust surface is trusted: the depth of the low band
// held out, when the surface fitted above it predicted it within twice its held-out RMSE.
void writeExtrapolationSection(const BenchFit& fit, std::ostringstream& md) {
  const VoltageBands& bands = fit.bands;
  const FitQuality& thrust = *fit.model.output(Output::kThrust).fit;
  md << "## Extrapolation\n\n";
  md << "Low band: fitted on the rows at " << formatPrintf("%.2f", bands.rest_min_v, "") << " V and above, judged on "
     << formatPrintf("%.2f", bands.low_min_v, "") << " to " << formatPrintf("%.2f", bands.low_max_v, "")
     << " V; high band: fitted below it, judged on " << formatPrintf("%.2f", bands.high_min_v, "") << " to "
     << formatPrintf("%.2f", bands.high_max_v, "") << " V.\n\n";
  const double depth_v = bands.rest_min_v - bands.low_min_v;
  if (!thrust.low_band_rmse) {
    md << "The chosen thrust surface (" << degrees(fit.model.output(Output::kThrust))
       << ") cannot be fitted without the low band, so its extrapolation is unchecked: **it is not trusted below "
       << formatPrintf("%.2f", bands.low_min_v, "") << " V**, the bench's lowest voltage.\n\n";
  } else if (*thrust.low_band_rmse <= 2.0 * thrust.held_out_rmse) {
    md << "Fitted without it, the chosen thrust surface predicts the low band within "
       << formatPrintf("%.3g", *thrust.low_band_rmse, "") << " " << fit.model.output(Output::kThrust).unit
       << " RMSE (held-out RMSE " << formatPrintf("%.3g", thrust.held_out_rmse, "")
       << "): **it is trusted about " << formatPrintf("%.2f", depth_v, "") << " V below the bench's lowest voltage, to "
       << formatPrintf("%.2f", bands.low_min_v - depth_v, "") << " V** (the depth of that check).\n\n";
  } else {
    md << "Fitted without it, the chosen thrust surface misses the low band by "
       << formatPrintf("%.3g", *thrust.low_band_rmse, "") << " RMSE, more than twice its held-out RMSE: **it is not "
       << "trusted below " << formatPrintf("%.2f", bands.low_min_v, "") << " V**, the bench's lowest voltage.\n\n";
  }
}

std::string score(double value) { return std::isnan(value) ? "-" : formatPrintf("%.4g", value, ""); }

void writeCandidatesSection(const BenchFit& fit, std::ostringstream& md) {
  md << "### Every candidate (held-out / low-band / high-band RMSE; - : not determined; x : falls with PWM or "
        "voltage in the covered domain)\n\n";
  for (Output output : kAllOutputs) {
    const OutputFitReport& report = fit.outputs[static_cast<int>(output)];
    if (report.candidates.empty()) continue;
    const std::optional<FitQuality>& chosen = fit.model.output(output).fit;
    md << "**" << outputName(output) << "** (" << report.unit << ")\n\n| candidate | held-out | low band | high "
       << "band |\n|---|---:|---:|---:|\n";
    for (const CandidateScore& c : report.candidates) {
      const bool drive = c.basis == "drive_curve";
      const std::string name =
          drive ? "drive curve " + std::to_string(c.pwm_degree) + (c.full_throttle ? " + full throttle" : "")
                : "(" + std::to_string(c.pwm_degree) + ", " + std::to_string(c.voltage_degree) + ")";
      const bool is_chosen = chosen && chosen->basis == c.basis && chosen->pwm_degree == c.pwm_degree &&
                             chosen->voltage_degree == c.voltage_degree &&
                             (!drive || c.full_throttle == std::isfinite(fullThrottleUs(fit.model.output(output))));
      md << "| " << (is_chosen ? "**" + name + "**" : name) << (c.physical ? "" : " x") << " | "
         << score(c.held_out_rmse) << " | " << score(c.low_band_rmse) << " | " << score(c.high_band_rmse) << " |\n";
    }
    md << "\n";
  }
}

void writeFiguresSection(std::ostringstream& md) {
  md << "## Figures\n\n";
  const char* captions[] = {
      "Outputs against PWM at each voltage level (thesis 4.1): bench points and the fitted surface's section at the "
      "level's voltage, drawn where the bench covered it; hollow points sit more than 0.5 V off their level "
      "(supply sag).",
      "Outputs against voltage at fixed PWM (thesis 4.2): the surface's section over the voltages covered at that PWM "
      "and the points of that PWM level (binned PWM: each point moved along the surface to the level's PWM, so the "
      "scatter is the noise).",
      "Residuals (fitted - measured) against PWM, coloured by voltage.",
      "The surfaces as contour maps over the covered domain (blank where the bench did not go), with the bench "
      "points."};
  for (std::size_t k = 0; k < fitReportFigures().size(); ++k) {
    md << captions[k] << "\n\n![" << fitReportFigures()[k] << "](" << fitReportFigures()[k] << ")\n\n";
  }
}

}  // namespace

std::string fitReportMarkdown(const BenchFit& fit, const std::string& model_path) {
  std::ostringstream md;
  writeVerdict(fit, model_path, md);
  writeDataSection(fit, md);
  writeQualitySection(fit, md);
  writeExtrapolationSection(fit, md);
  writeCandidatesSection(fit, md);
  writeFiguresSection(md);
  return md.str();
}

}  // namespace fitting
}  // namespace propulsion_estimator
