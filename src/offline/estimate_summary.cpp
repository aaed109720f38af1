#include "propulsion_estimator/offline/estimate_summary.h"

#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace offline {
namespace {

std::string number(double value, const char* pattern) { return formatPrintf(pattern, value, "n/a"); }

std::string hoverTable(const FlightEstimate& e) {
  if (e.hovers.empty()) return "No hover was found (see the warnings).\n";
  std::string text =
      "| # | from (s) | to (s) | total mass (kg) | std (kg) | payload (kg) | averaged over (s) | battery (V) | "
      "thrust/weight | payload margin (kg) |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < e.hovers.size(); ++i) {
    const HoverEpisode& h = e.hovers[i];
    text += "| " + std::to_string(i + 1) + " | " + number(h.start_s, "%.1f") + " | " + number(h.end_s, "%.1f") +
            " | " + number(h.total_mass_kg, "%.3f") + " | " + number(h.mass_std_kg, "%.3f") + " | " +
            number(h.payload_kg, "%.3f") + " | " + number(h.window_s, "%.1f") + " | " + number(h.voltage_v, "%.2f") +
            " | " + number(h.thrust_to_weight, "%.2f") + " | " + number(h.max_additional_payload_kg, "%.3f") + " |\n";
  }
  return text;
}

std::string motorHealth(const FlightEstimate& e) {
  const MotorHealthVerdict& v = e.motor_health;
  if (!v.judged) return "Not judged: " + v.unavailable + ".\n";
  std::string text = "Last window of " + std::to_string(v.blocks) + " steady-hover blocks: ";
  text += v.flagged_channel == 0 ? "no motor stands out.\n" : "channel " + std::to_string(v.flagged_channel) +
                                                                  " stands out.\n";
  text += "\n| channel | thrust it lacks | std |\n|---|---|---|\n";
  for (const MotorBalanceGap& m : v.motors) {
    text += "| " + std::to_string(m.channel) + " | " + number(100.0 * m.thrust_gap, "%.1f %%") + " | " +
            number(100.0 * m.thrust_gap_std, "%.1f %%") + " |\n";
  }
  return text;
}

std::string escCheck(const FlightEstimate& e) {
  const ModelCheckReport& r = e.esc_check;
  if (!r.telemetry_seen) return "Not judged: the log carries no ESC telemetry.\n";
  if (r.verdict == ModelCheckVerdict::kNotJudged) return "Not judged: " + r.note + ".\n";
  std::string text = "Last judgement: **" + std::string(modelCheckVerdictName(r.verdict)) + "**" +
                     (r.flagged_channel != 0 ? " on channel " + std::to_string(r.flagged_channel) : std::string()) +
                     " (" + r.note + ").\n";
  text += "\n| channel | hover rpm / model | hover current / model |\n|---|---|---|\n";
  for (const MotorCheck& m : r.motors) {
    text += "| " + std::to_string(m.channel) + " | " + number(m.hover_rpm_ratio, "%.3f") + " | " +
            number(m.hover_current_ratio, "%.3f") + " |\n";
  }
  text += "\nSupply resistance (battery to ESCs): " + number(r.supply_resistance_ohm, "%.4f ohm") + ".\n";
  text += "\nVerdicts other than consistent during the flight: " +
          (e.esc_flags.empty() ? std::string("none") : nameList(e.esc_flags, 8)) + ".\n";
  return text;
}

}  // namespace

std::string estimateSummaryMarkdown(const FlightEstimate& e, const std::string& model_name,
                                    const std::string& figure) {
  std::string text = "# Estimate of " + e.source + "\n\n";
  text += "The estimator's onboard session run on the log message by message, as `estimator_node` runs it on a "
          "replayed bag. Model: `" + model_name + "`. Empty mass: " + number(e.empty_mass_kg, "%.3f kg") + " (" +
          e.empty_mass_source + ").\n\n";
  if (!figure.empty()) text += "![mass and payload over time](" + figure + ")\n\n";
  text += "## Hover episodes\n\n" + hoverTable(e);
  text += "\nThe mass of an episode is the hover average at its last sample (the node's `~payload` "
          "`total_mass_kg`); the payload margin keeps the minimum thrust-to-weight at the present voltage.\n";
  text += "\n## Motor health\n\n" + motorHealth(e);
  text += "\n## Live ESC check\n\n" + escCheck(e);
  const EstimatorCounters& c = e.counters;
  text += "\n## Inputs\n\n" + std::to_string(c.accepted) + " RCOut messages estimated, " +
          std::to_string(c.rejected[static_cast<int>(Rejection::kDisarmed)]) + " disarmed or stopped; " +
          std::to_string(c.motor_samples_outside_domain) + " of " + std::to_string(c.motor_samples) +
          " motor samples outside the model's domain.\n";
  text += "\n## Warnings\n\n";
  if (e.warnings.empty()) text += "None.\n";
  for (const std::string& w : e.warnings) text += "- " + w + "\n";
  return text;
}

}  // namespace offline
}  // namespace propulsion_estimator
