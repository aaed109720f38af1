#include "propulsion_estimator/gap/gap_report.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/model/effect_description.h"

namespace propulsion_estimator {
namespace gap {
namespace {

void emitNumber(YAML::Emitter& out, double value, const char* pattern = "%.4g") {
  if (std::isfinite(value)) {
    out << YAML::Value << formatPrintf(pattern, value);
  } else {
    out << YAML::Value << YAML::Null;
  }
}

// A key and its number: null when not finite.
void emitField(YAML::Emitter& out, const char* key, double value, const char* pattern = "%.4g") {
  out << YAML::Key << key;
  emitNumber(out, value, pattern);
}

void emitStats(YAML::Emitter& out, const ResidualStats& stats) {
  out << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "samples" << YAML::Value << stats.samples;
  emitField(out, "bias_pct", stats.bias_pct);
  emitField(out, "rmse_pct", stats.rmse_pct);
  emitField(out, "bias_n", stats.bias_n);
  emitField(out, "rmse_n", stats.rmse_n);
  out << YAML::EndMap;
}

std::string statsRow(const std::string& label, const ResidualStats& stats) {
  return "| " + label + " | " + std::to_string(stats.samples) + " | " + formatPrintf("%.2f", stats.bias_pct, "n/a") +
         " | " + formatPrintf("%.2f", stats.rmse_pct, "n/a") + " | " + formatPrintf("%.3f", stats.bias_n, "n/a") +
         " |\n";
}

std::vector<std::string> kindNames(const std::vector<effects::Kind>& kinds) {
  std::vector<std::string> names;
  for (effects::Kind kind : kinds) names.push_back(effects::kindName(kind));
  return names;
}

// The effects' names as Markdown code, joined: "`a`, `b`".
std::string codeList(const std::vector<effects::Kind>& kinds) {
  std::vector<std::string> names;
  for (effects::Kind kind : kinds) names.push_back("`" + std::string(effects::kindName(kind)) + "`");
  return joined(names);
}

void emitNested(YAML::Emitter& out, const NestedHoldOut& nested) {
  out << YAML::Key << "nested" << YAML::Value << YAML::BeginMap;
  if (!nested.unavailable.empty()) {
    out << YAML::Key << "unavailable" << YAML::Value << nested.unavailable << YAML::EndMap;
    return;
  }
  emitField(out, "before_rmse_pct", nested.before_rmse_pct);
  emitField(out, "after_rmse_pct", nested.after_rmse_pct);
  emitField(out, "before_bias_pct", nested.before_bias_pct);
  emitField(out, "after_bias_pct", nested.after_bias_pct);
  out << YAML::Key << "folds" << YAML::Value << YAML::BeginSeq;
  for (const NestedFold& fold : nested.folds) {
    out << YAML::BeginMap << YAML::Key << "fitted_on" << YAML::Value << YAML::Flow << fold.fitted_on;
    out << YAML::Key << "scored_on" << YAML::Value << YAML::Flow << fold.scored_on;
    out << YAML::Key << "effects" << YAML::Value << YAML::Flow << kindNames(fold.effects);
    out << YAML::Key << "suspect_motor" << YAML::Value;
    if (fold.suspect_channel) {
      out << *fold.suspect_channel;
    } else {
      out << YAML::Null;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
}

// Every candidate's line, what was selected, the ambiguous groups and the selection's trace.
void emitSelection(YAML::Emitter& out, const Diagnosis& diagnosis) {
  out << YAML::Key << "effects" << YAML::Value << YAML::BeginSeq;
  for (const EffectResult& effect : diagnosis.effects) {
    const effects::ParameterSpec& spec = effects::parameterSpec(effect.kind);
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << effects::kindName(effect.kind);
    out << YAML::Key << "testable" << YAML::Value << effect.testable;
    if (effect.testable) {
      out << YAML::Key << "params" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << spec.key;
      emitNumber(out, effect.parameter);
      out << YAML::EndMap;
      out << YAML::Key << "ci" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << spec.key
          << YAML::Value << YAML::Flow << YAML::BeginSeq << formatPrintf("%.4g", effect.ci_low)
          << formatPrintf("%.4g", effect.ci_high) << YAML::EndSeq << YAML::EndMap;
      out << YAML::Key << "plausible" << YAML::Value << effect.plausible;
      emitField(out, "heldout_rmse_pct", effect.heldout_rmse_pct);
      emitField(out, "joint_rmse_pct", effect.joint_rmse_pct);
      emitField(out, "base_joint_rmse_pct", effect.base_joint_rmse_pct);
      emitField(out, "p_value", effect.p_value);
      emitField(out, "current_view_ratio", effect.current_view_ratio, "%.3f");
      emitField(out, "largest_change_pct", effect.size.largest_change_pct);
      emitField(out, "parts_change_pct", effect.size.parts_change_pct);
      out << YAML::Key << "blocks_beyond_parts" << YAML::Value << effect.size.blocks_beyond;
      emitField(out, "parts_imitated_share", effect.size.imitated_share, "%.3f");
    }
    out << YAML::Key << "reason" << YAML::Value << effect.reason;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "selected" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (effects::Kind kind : diagnosis.selected) out << effects::kindName(kind);
  out << YAML::EndSeq;
  out << YAML::Key << "background" << YAML::Value << YAML::Flow << kindNames(diagnosis.background);
  out << YAML::Key << "ambiguous" << YAML::Value << YAML::BeginSeq;
  for (const Ambiguity& ambiguity : diagnosis.ambiguous) out << YAML::Flow << kindNames(ambiguity.kinds);
  out << YAML::EndSeq;
  out << YAML::Key << "ambiguity" << YAML::Value << YAML::BeginSeq;
  for (const Ambiguity& ambiguity : diagnosis.ambiguous) {
    out << YAML::BeginMap << YAML::Key << "effects" << YAML::Value << YAML::Flow << kindNames(ambiguity.kinds);
    emitField(out, "swap_loss_pct", ambiguity.swap_loss_pct);
    emitField(out, "swap_p_value", ambiguity.swap_p_value);
    out << YAML::Key << "separating_flight" << YAML::Value << ambiguity.separating_flight << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "trace" << YAML::Value << YAML::BeginSeq;
  for (const SelectionStep& step : diagnosis.trace) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "round" << YAML::Value << step.round << YAML::Key << "name"
        << YAML::Value << effects::kindName(step.kind);
    emitField(out, "heldout_rmse_pct", step.heldout_rmse_pct);
    emitField(out, "base_heldout_rmse_pct", step.base_heldout_rmse_pct);
    if (std::isfinite(step.rpm_rmse_pct)) {
      emitField(out, "rpm_rmse_pct", step.rpm_rmse_pct);
      emitField(out, "base_rpm_rmse_pct", step.base_rpm_rmse_pct);
    }
    emitField(out, "joint_rmse_pct", step.joint_rmse_pct);
    emitField(out, "p_value", step.p_value);
    if (step.regional.blocks > 0) {
      out << YAML::Key << "regional_blocks" << YAML::Value << step.regional.blocks;
      emitField(out, "regional_rmse_pct", step.regional.pwm_rmse_pct);
      emitField(out, "base_regional_rmse_pct", step.regional.base_pwm_rmse_pct);
      if (std::isfinite(step.regional.rpm_rmse_pct)) {
        emitField(out, "regional_rpm_rmse_pct", step.regional.rpm_rmse_pct);
        emitField(out, "base_regional_rpm_rmse_pct", step.regional.base_rpm_rmse_pct);
      }
    }
    out << YAML::Key << "verdict" << YAML::Value << step.verdict << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

}  // namespace

namespace {

// The report's gap section: overall, the blocks used and left out, per flight and per bench log.
void emitGap(YAML::Emitter& out, const Diagnosis& diagnosis) {
  out << YAML::Key << "gap" << YAML::Value << YAML::BeginMap;
  emitField(out, "bias_pct", diagnosis.overall.bias_pct);
  emitField(out, "rmse_pct", diagnosis.overall.rmse_pct);
  emitField(out, "payload_err_pct", diagnosis.payload_err_pct);
  out << YAML::Key << "samples" << YAML::Value << diagnosis.overall.samples;
  out << YAML::Key << "transient_samples" << YAML::Value << diagnosis.transient_blocks;
  out << YAML::Key << "dynamic_samples" << YAML::Value << diagnosis.dynamic_blocks;
  emitField(out, "rotor_time_constant_s", diagnosis.rotor_time_constant_s);
  out << YAML::Key << "rotor_lag" << YAML::Value << diagnosis.rotor_lag;
  out << YAML::Key << "flights" << YAML::Value << YAML::BeginSeq;
  for (const FlightGap& flight : diagnosis.flights) {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << flight.name;
    emitField(out, "mean_mass_kg", flight.mean_mass_kg);
    out << YAML::Key << "stats" << YAML::Value;
    emitStats(out, flight.stats);
    out << YAML::Key << "problems" << YAML::Value << YAML::Flow << flight.problems;
    out << YAML::Key << "segments" << YAML::Value << YAML::BeginSeq;
    for (const ManifestSegment& segment : flight.segments) {
      // As the manifest gave them (5.2, not 5.2000000000000002).
      out << YAML::Flow << YAML::BeginMap;
      emitField(out, "start", segment.start_s, "%.10g");
      emitField(out, "end", segment.end_s, "%.10g");
      emitField(out, "mass_kg", segment.mass_kg, "%.10g");
      out << YAML::EndMap;
    }
    out << YAML::EndSeq << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "bench" << YAML::Value << YAML::BeginSeq;
  for (const BenchGap& bench : diagnosis.bench) {
    out << YAML::BeginMap << YAML::Key << "source" << YAML::Value << bench.source;
    out << YAML::Key << "stats" << YAML::Value;
    emitStats(out, bench.stats);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
}

}  // namespace

std::string gapReportYaml(const Diagnosis& diagnosis) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  emitGap(out, diagnosis);

  out << YAML::Key << "where" << YAML::Value << YAML::BeginMap;
  for (const Breakdown& breakdown : diagnosis.where) {
    out << YAML::Key << breakdown.name << YAML::Value;
    if (!breakdown.unavailable.empty()) {
      out << YAML::Flow << YAML::BeginMap << YAML::Key << "unavailable" << YAML::Value << breakdown.unavailable
          << YAML::EndMap;
      continue;
    }
    out << YAML::BeginSeq;
    for (const Bin& bin : breakdown.bins) {
      out << YAML::Flow << YAML::BeginMap << YAML::Key << "bin" << YAML::Value << bin.label;
      out << YAML::Key << "samples" << YAML::Value << bin.stats.samples;
      emitField(out, "bias_pct", bin.stats.bias_pct);
      emitField(out, "rmse_pct", bin.stats.rmse_pct);
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  out << YAML::Key << "motor_basis" << YAML::Value << motorBasisName(diagnosis.motors.basis);
  emitField(out, "reference_thrust_factor", diagnosis.motors.reference_thrust_factor);
  out << YAML::Key << "motors" << YAML::Value << YAML::BeginSeq;
  for (const MotorGap& motor : diagnosis.motors.motors) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "channel" << YAML::Value << motor.channel;
    emitField(out, "thrust_gap_pct", motor.thrust_gap_pct);
    emitField(out, "ci_pct", motor.ci_pct);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "suspect_motor" << YAML::Value;
  if (diagnosis.motors.suspect_channel) {
    out << *diagnosis.motors.suspect_channel;
  } else {
    out << YAML::Null;
  }
  emitField(out, "suspect_thrust_factor", diagnosis.motors.suspect_thrust_factor);
  out << YAML::Key << "centre_of_thrust_m" << YAML::Value << YAML::Flow << YAML::BeginSeq
      << formatPrintf("%.4f", diagnosis.motors.cg_offset_x_m) << formatPrintf("%.4f", diagnosis.motors.cg_offset_y_m)
      << YAML::EndSeq;
  if (!diagnosis.motors.unavailable.empty()) {
    out << YAML::Key << "motors_unavailable" << YAML::Value << diagnosis.motors.unavailable;
  }
  out << YAML::EndMap;

  emitSelection(out, diagnosis);
  out << YAML::Key << "heldout" << YAML::Value << YAML::BeginMap;
  emitField(out, "before_rmse_pct", diagnosis.heldout.before_rmse_pct);
  emitField(out, "after_rmse_pct", diagnosis.heldout.after_rmse_pct);
  emitField(out, "before_bias_pct", diagnosis.heldout.before_bias_pct);
  emitField(out, "after_bias_pct", diagnosis.heldout.after_bias_pct);
  emitField(out, "before_payload_err_pct", diagnosis.heldout.before_payload_err_pct);
  emitField(out, "after_payload_err_pct", diagnosis.heldout.after_payload_err_pct);
  emitNested(out, diagnosis.heldout.nested);
  out << YAML::EndMap;
  out << YAML::Key << "method" << YAML::Value << diagnosis.method;
  out << YAML::Key << "problems" << YAML::Value << diagnosis.problems;
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void writeGapReportData(const Diagnosis& diagnosis, const std::string& directory) {
  std::ofstream csv = openReportFile(directory, "gap_samples.csv");
  csv << "flight,time_s,truth_n,model_n,current_view_n,rpm_view_n,corrected_n,pwm_us,voltage_v,current_a";
  // The battery current is current_a's.
  const auto columns = [](effects::Signal signal) { return signal != effects::Signal::kBatteryCurrent; };
  for (effects::Signal signal : effects::allSignals()) {
    if (columns(signal)) csv << "," << effects::signalKey(signal);
  }
  csv << ",flight_time_s,hover\n";
  const auto cell = [](double value) { return std::isfinite(value) ? formatPrintf("%.6g", value) : std::string(); };
  for (const GapSample& s : diagnosis.samples) {
    csv << s.flight << "," << cell(s.time_s) << "," << cell(s.truth_n) << "," << cell(s.model_n) << ","
        << cell(s.current_view_n) << "," << cell(s.rpm_view_n) << "," << cell(s.corrected_n) << "," << cell(s.pwm_us)
        << "," << cell(s.voltage_v) << "," << cell(s.current_a);
    for (effects::Signal signal : effects::allSignals()) {
      if (columns(signal)) csv << "," << cell(s.signals.value(signal));
    }
    csv << "," << cell(s.flight_time_s) << "," << (s.hover ? 1 : 0) << "\n";
  }
  std::ofstream selected = openReportFile(directory, "gap_selected.csv");
  selected << "name\n";
  for (effects::Kind kind : diagnosis.selected) selected << effects::kindName(kind) << "\n";
}

const std::vector<std::string>& gapReportFigures() {
  static const std::vector<std::string> figures = {"gap_signals.png", "gap_two_views.png", "gap_before_after.png"};
  return figures;
}

namespace {

// What the motors were judged against, for the report.
std::string basisText(const MotorBalance& balance) {
  if (balance.basis == MotorBasis::kReference) {
    return "Each motor against this vehicle's own healthy flights (--reference): the fraction of its modelled thrust "
           "it lacks now that it did not then (negative: more), the yaw balance's change fitted beside it (a damaged "
           "propeller's drag torque changes too). A suspect lacks more than the motor gap threshold and three "
           "standard errors of the reference's flight-to-flight spread. The effects are sought as changes from that "
           "vehicle: its thrust on those flights was " +
           formatPrintf("%.3f", balance.reference_thrust_factor) + " of the model's (1: not weighed there).";
  }
  if (balance.basis == MotorBasis::kPayloads) {
    return "Each motor's gap that keeps the empty vehicle's mass moment the same with every payload (the payloads "
           "hang below base_link's origin). A gap resting on its search bound or without an interval names no motor, "
           "nor one within three times the spread healthy vehicles show (+-" +
           formatPrintf("%.1f", balance.healthy_gap_std_pct) +
           " %): their parts differ, and a payload hung a millimetre off moves a gap by a few per cent. A reference of "
           "this vehicle's healthy flights (--reference) would sharpen it.";
  }
  return "Each motor against the ideal balance of identical rotors. Healthy vehicles are never there: their parts "
         "differ and propellers of the two spin directions are not mirror images, so a gap is a suspect only beyond "
         "three times the spread healthy vehicles show (+-" + formatPrintf("%.1f", balance.healthy_gap_std_pct) +
         " %, one standard deviation). A reference of this vehicle's healthy flights (--reference) would sharpen it.";
}

// Section 2 of the Markdown report: the residual's breakdowns and the motors' balance.
void writeWhereSection(std::ostream& md, const Diagnosis& diagnosis) {
  md << "## 2. Where it lies\n\n";
  for (const Breakdown& breakdown : diagnosis.where) {
    md << "### " << breakdown.name << "\n\n";
    if (!breakdown.unavailable.empty()) {
      md << "Not available: " << breakdown.unavailable << ".\n\n";
      continue;
    }
    md << "| bin | samples | bias % | RMSE % | bias N |\n|---|---|---|---|---|\n";
    for (const Bin& bin : breakdown.bins) md << statsRow(bin.label, bin.stats);
    md << "\n";
  }
  for (const BenchGap& bench : diagnosis.bench) {
    for (const Breakdown& breakdown : bench.where) {
      md << "### bench " << bench.source << ": " << breakdown.name << "\n\n";
      if (!breakdown.unavailable.empty()) {
        md << "Not available: " << breakdown.unavailable << ".\n\n";
        continue;
      }
      md << "| bin | samples | bias % | RMSE % | bias N |\n|---|---|---|---|---|\n";
      for (const Bin& bin : breakdown.bins) md << statsRow(bin.label, bin.stats);
      md << "\n";
    }
  }
  md << "### Motors (moment balance in steady hover)\n\n";
  if (!diagnosis.motors.unavailable.empty()) {
    md << "Not available: " << diagnosis.motors.unavailable << ".\n\n";
  } else {
    md << basisText(diagnosis.motors) << "\n\n| channel | thrust gap % | 95 % interval +- |\n|---|---|---|\n";
    for (const MotorGap& motor : diagnosis.motors.motors) {
      md << "| " << motor.channel << " | " << formatPrintf("%.2f", motor.thrust_gap_pct, "n/a") << " | "
         << formatPrintf("%.2f", motor.ci_pct, "n/a") << " |\n";
    }
    md << "\nCentre of thrust: x " << formatPrintf("%.1f", 1000.0 * diagnosis.motors.cg_offset_x_m, "n/a") << " mm, y "
       << formatPrintf("%.1f", 1000.0 * diagnosis.motors.cg_offset_y_m, "n/a") << " mm from base_link. ";
    if (diagnosis.motors.suspect_channel) {
      md << "**Suspect motor: channel " << *diagnosis.motors.suspect_channel << "**. It gives "
         << formatPrintf("%.1f", 100.0 * diagnosis.motors.suspect_thrust_factor, "n/a")
         << " % of its modelled thrust ("
         << (diagnosis.motors.basis == MotorBasis::kPayloads ? "fitted to the weighed thrust" : "from its share of the thrust")
         << "); that is applied before effects are sought.\n\n";
    } else {
      md << "No motor stands out.\n\n";
    }
  }

}

// Section 3 of the Markdown report: one line per candidate effect, the selection and its rounds.
void writeEffectsSection(std::ostream& md, const Diagnosis& diagnosis) {
  md << "## 3. Which effect\n\n" << diagnosis.method << "\n\n";
  md << "| effect | testable | parameter | 95 % interval | held-out RMSE % | joint RMSE %, before -> with it | p "
        "(joint) | current-view ratio | verdict |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const EffectResult& effect : diagnosis.effects) {
    const effects::ParameterSpec& spec = effects::parameterSpec(effect.kind);
    md << "| " << effects::kindName(effect.kind) << " | " << (effect.testable ? "yes" : "no") << " | ";
    if (effect.testable) {
      md << spec.key << " = " << formatPrintf("%.4g", effect.parameter) << " | " << formatPrintf("%.4g", effect.ci_low)
         << " .. " << formatPrintf("%.4g", effect.ci_high) << " | "
         << formatPrintf("%.2f", effect.heldout_rmse_pct, "n/a") << " | "
         << formatPrintf("%.2f", effect.base_joint_rmse_pct, "n/a") << " -> "
         << formatPrintf("%.2f", effect.joint_rmse_pct, "n/a") << " | " << formatPrintf("%.3f", effect.p_value, "n/a")
         << " | " << formatPrintf("%.2f", effect.current_view_ratio, "n/a") << " | ";
    } else {
      md << " | | | | | | ";
    }
    md << effect.reason << " |\n";
  }
  md << "\n**Selected:** ";
  if (diagnosis.selected.empty()) {
    md << (diagnosis.ambiguous.empty() ? "none of the known effects explains the gap significantly.\n\n"
                                       : "none established.\n\n");
  } else {
    for (std::size_t k = 0; k < diagnosis.selected.size(); ++k) {
      md << (k ? ", " : "") << effects::kindName(diagnosis.selected[k]);
    }
    md << ".\n\n";
    for (effects::Kind kind : diagnosis.selected) md << "- `" << effects::kindName(kind) << "`: " << effects::describe(kind).meaning << ".\n";
    md << "\n";
  }
  if (!diagnosis.background.empty()) {
    md << "**Modelled, not named:** " << codeList(diagnosis.background) << ": the vehicle's own (no change from its healthy flights, or within its parts' spread: its line in the "
          "table above says which), in the correction, where it lowers the held-out error, and, when it was "
          "modelled before any name, beneath the effects tried after it, so that what it explains does not hide a small "
          "effect.\n\n";
  }
  for (const Ambiguity& ambiguity : diagnosis.ambiguous) {
    md << "**Ambiguous: one of " << codeList(ambiguity.kinds) << "** explains part of the gap, but these flights cannot tell which: swapping the leader for the runner-up "
          "raises the joint held-out error by only "
       << formatPrintf("%.3f", ambiguity.swap_loss_pct) << " points (sign-flip p = "
       << formatPrintf("%.3f", ambiguity.swap_p_value) << "). The correction uses the leader. The flight that would "
       << "separate them: " << ambiguity.separating_flight << ".\n\n";
  }
  if (!diagnosis.trace.empty()) {
    md << "Selection, round by round (held-out RMSE of the PWM view, and of the views together):\n\n"
          "| round | candidate | held-out RMSE % | joint RMSE % | p | verdict |\n|---|---|---|---|---|---|\n";
    for (const SelectionStep& step : diagnosis.trace) {
      md << "| " << step.round << " | " << effects::kindName(step.kind) << " | " << formatPrintf("%.2f", step.heldout_rmse_pct, "n/a") << " | "
         << formatPrintf("%.2f", step.joint_rmse_pct, "n/a") << " | " << formatPrintf("%.3f", step.p_value, "n/a") << " | " << step.verdict << " |\n";
    }
    md << "\n";
  }
  md << "The two views of thrust tell causes apart: the PWM view (what the node estimates) and the view through the "
        "measured battery current. The current-view ratio is how much of an effect's correction the current view's "
        "residual shows: about 1 for a thrust loss or a hidden mass, near 0 for an ESC offset, a third to a half for an "
        "electrical or an air-density cause, negative for motor heating.\n\n";

}

// The nested hold-out's figures and what each outer fold chose.
void writeNestedSection(std::ostream& md, const NestedHoldOut& nested) {
  md << "These figures are optimistic: the flights that score them also selected the effects. Nested hold-out, "
        "every flight scored by a diagnosis (suspect motor, selection, fit) that never saw it (the rotor lag and the "
        "blocks' steady/dynamic split excepted, chosen on all flights): ";
  if (!nested.unavailable.empty()) {
    md << "not available: " << nested.unavailable << ".\n\n";
    return;
  }
  md << "RMSE " << formatPrintf("%.2f", nested.before_rmse_pct) << " % with the plain model, "
     << formatPrintf("%.2f", nested.after_rmse_pct) << " % corrected (bias " << formatPrintf("%.2f", nested.before_bias_pct)
     << " % -> " << formatPrintf("%.2f", nested.after_bias_pct) << " %).\n\n| scored on | chosen on | effects | suspect |\n"
     << "|---|---|---|---|\n";
  for (const NestedFold& fold : nested.folds) {
    md << "| " << joined(fold.scored_on) << " | " << joined(fold.fitted_on) << " | "
       << (fold.effects.empty() ? std::string("none") : joined(kindNames(fold.effects))) << " | "
       << (fold.suspect_channel ? std::to_string(*fold.suspect_channel) : std::string("none")) << " |\n";
  }
  md << "\n";
}

}  // namespace

std::string gapReportMarkdown(const Diagnosis& diagnosis, const PropulsionModel& model, const std::string& command) {
  std::ostringstream md;
  const ModelMetadata& meta = model.metadata();
  md << "# Where the model and the flights part\n\n";
  md << "Model: " << meta.esc << " / " << meta.motor << " / " << meta.propeller << " (" << meta.source << ").  \n";
  md << "Command: `" << command << "`\n\n";
  md << "The residual is the model's vertical thrust minus the thrust that flew (weighed mass x vertical specific "
        "force from the IMU), in percent of the latter: positive when the model reads high. Samples are "
        "quasi-steady blocks: "
     << diagnosis.transient_blocks << " transient blocks (the rotors spinning up or down, where thrust lags the PWM) "
        "are left out of everything below; "
     << diagnosis.dynamic_blocks << " more, not steady, are used with the rotors' lag modelled (" << diagnosis.rotor_lag
     << ").\n\n";

  md << "## 1. The gap\n\n";
  md << "| | samples | bias % | RMSE % | bias N |\n|---|---|---|---|---|\n";
  md << statsRow("all flights", diagnosis.overall);
  for (const FlightGap& flight : diagnosis.flights) md << statsRow(flight.name, flight.stats);
  for (const BenchGap& bench : diagnosis.bench) md << statsRow("bench: " + bench.source, bench.stats);
  md << "\nWeighed segments used (s on each log's clock, kg; a flight given one mass for the whole flight: the "
        "airborne stretches found in its log):\n\n";
  for (const FlightGap& flight : diagnosis.flights) {
    std::vector<std::string> spans;
    for (const ManifestSegment& segment : flight.segments) {
      spans.push_back(formatPrintf("%.1f", segment.start_s) + "-" + formatPrintf("%.1f", segment.end_s) + " s at " +
                      formatPrintf("%.3f", segment.mass_kg) + " kg");
    }
    md << "- " << flight.name << ": " << joined(spans) << "\n";
  }
  md << "\nPayload error of the node, tare on the lightest weighed segment: "
     << formatPrintf("%.2f", diagnosis.payload_err_pct, "n/a") << " % (RMS over the heavier segments).\n\n";
  if (!diagnosis.problems.empty()) {
    md << "What could not be used:\n\n";
    for (const std::string& problem : diagnosis.problems) md << "- " << problem << "\n";
    md << "\n";
  }

  writeWhereSection(md, diagnosis);
  writeEffectsSection(md, diagnosis);
  md << "## 4. How far it shrinks (held-out flights)\n\n";
  md << "| | before | after |\n|---|---|---|\n";
  md << "| RMSE % | " << formatPrintf("%.2f", diagnosis.heldout.before_rmse_pct, "n/a") << " | "
     << formatPrintf("%.2f", diagnosis.heldout.after_rmse_pct, "n/a") << " |\n";
  md << "| bias % | " << formatPrintf("%.2f", diagnosis.heldout.before_bias_pct, "n/a") << " | "
     << formatPrintf("%.2f", diagnosis.heldout.after_bias_pct, "n/a") << " |\n";
  md << "| payload error % | " << formatPrintf("%.2f", diagnosis.heldout.before_payload_err_pct, "n/a") << " | "
     << formatPrintf("%.2f", diagnosis.heldout.after_payload_err_pct, "n/a") << " |\n\n";
  writeNestedSection(md, diagnosis.heldout.nested);

  md << "## Figures\n\n";
  md << "![Residual against each signal](gap_signals.png)\n\n"
        "Residual against each signal; orange: what the diagnosis's correction predicts: corrected_model.yaml's "
        "effects and, when a motor is suspect, its factor (which the model file does not carry).\n\n";
  md << "![The two views](gap_two_views.png)\n\n"
        "Current-view residual against PWM-view residual; the lines show how each family of causes moves them.\n\n";
  md << "![Before and after](gap_before_after.png)\n\n"
        "Residual over time per flight, with the plain model and with the diagnosis's correction (as above).\n";
  return md.str();
}

}  // namespace gap
}  // namespace propulsion_estimator
