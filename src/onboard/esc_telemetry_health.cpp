#include "propulsion_estimator/onboard/esc_telemetry_health.h"

#include <cmath>

#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace {

std::string massViewText(const OnboardSession& session, double now_s) {
  if (session.rpmViewInUse(now_s)) return "rpm";
  return session.config().mass_view == "rpm" ? "pwm (rpm chosen: no rpm-view mass yet or telemetry stale)" : "pwm";
}

}  // namespace

HealthStatus judgeEscTelemetry(const OnboardSession& session, double now_s, const EscInputActivity& activity) {
  const ModelCheckReport report = session.modelCheck().report(now_s);
  HealthStatus status;
  auto add = [&status](std::string key, std::string value) { status.values.emplace_back(std::move(key), std::move(value)); };
  const std::size_t motors = report.motors.size();
  add("topics", activity.topics);
  add("messages", std::to_string(activity.received));
  add("undecodable", std::to_string(activity.undecodable));
  add("fresh_motors", std::to_string(report.fresh_motors) + " of " + std::to_string(motors));
  add("verdict", modelCheckVerdictName(report.verdict));
  add("flagged_channel", std::to_string(report.flagged_channel));
  for (const MotorCheck& m : report.motors) {
    add("channel " + std::to_string(m.channel) + " hover rpm / current ratio",
        formatPrintf("%.3f", m.hover_rpm_ratio) + " / " + formatPrintf("%.3f", m.hover_current_ratio));
  }
  add("supply_resistance_ohm", formatPrintf("%.4f", report.supply_resistance_ohm) + " +- " +
                                   formatPrintf("%.4f", report.supply_resistance_std_ohm));
  const double applied_ohm = session.supplyAppliedOhm();
  add("supply_resistance_applied", std::isnan(applied_ohm) ? std::string("no") : formatPrintf("%.4f ohm", applied_ohm));
  add("advice", modelCheckAdvice(report.verdict));
  add("mass_view", massViewText(session, now_s));
  const auto& rpm_view = session.rpmView();
  add("rpm_view_mass_kg", rpm_view ? formatPrintf("%.3f", rpm_view->massKg()) : std::string("no thrust_from_rpm"));
  if (rpm_view && rpm_view->atBenchAir()) {
    add("rpm_view_air", "the bench's air density (no static pressure and air temperature): off by the density "
                        "ratio on another day's air");
  }
  add("pwm_view_mass_kg", formatPrintf("%.3f", session.estimator().output().payload.total_mass_kg));
  if (!report.telemetry_seen) {
    status.message = activity.undecodable > 0
                         ? "no usable ESC telemetry (" + activity.last_error + "): nothing measured, model check off"
                         : "no ESC telemetry: nothing measured, model check off, estimates unchanged";
    return status;
  }
  if (report.fresh_motors < static_cast<int>(motors)) {
    status.level = HealthLevel::kWarn;
    status.message = "ESC telemetry stale on " + std::to_string(motors - report.fresh_motors) + " of " +
                     std::to_string(motors) + " motors: measured values NaN, averages held, estimates unchanged; " +
                     report.note;
    return status;
  }
  const bool flagged = report.verdict == ModelCheckVerdict::kPropeller ||
                       report.verdict == ModelCheckVerdict::kMotorEsc || report.verdict == ModelCheckVerdict::kSupply;
  status.level = flagged ? HealthLevel::kWarn : HealthLevel::kOk;
  status.message = report.note + (flagged ? std::string(": ") + modelCheckAdvice(report.verdict) : std::string());
  return status;
}

}  // namespace propulsion_estimator
