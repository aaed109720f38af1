// Why nothing, or little, of the flights could be used: one line each, with the numbers.
#include <algorithm>
#include <limits>

#include "diagnoser.h"

namespace propulsion_estimator {
namespace gap {
namespace detail {

std::string nothingUsable(const UnusedData& unused, const DiagnosisConfig& config,
                          const std::vector<std::string>& skipped) {
  std::string reasons;
  const auto add = [&reasons](const std::string& reason) { reasons += (reasons.empty() ? "" : "; ") + reason; };
  if (unused.transient > 0) {
    add(std::to_string(unused.transient) + " blocks transient (collective PWM changing by more than " +
        formatNumber(config.max_pwm_change_us) + " us or accelerating faster than " +
        formatNumber(config.max_accel_m_s2) + " m/s^2 vertically within " + formatNumber(config.block_s) + " s)");
  }
  if (unused.without_attitude > 0) {
    add(std::to_string(unused.without_attitude) + " blocks without the attitude on every frame (no IMU orientation within " +
        formatNumber(config.signal_timeout_s) + " s)");
  }
  if (unused.frames_without_battery > 0) {
    add(std::to_string(unused.frames_without_battery) + " rc/out frames without a battery voltage within " +
        formatNumber(config.signal_timeout_s) + " s");
  }
  if (unused.rejected_outside > 0) {
    add(std::to_string(unused.rejected_outside) +
        " blocks outside the model's domain, which it rejects (outside: reject) as the node would");
  }
  // The skipped segments' reasons are the reasons when no block was cut at all: the refusal is
  // the only line the user sees, so it carries them.
  if (reasons.empty()) {
    for (const std::string& reason : skipped) add(reason);
  }
  return "no usable sample in any weighed segment of any flight" + (reasons.empty() ? std::string() : ": " + reasons);
}

std::optional<std::string> outsideTheDomain(const std::vector<Block>& blocks, const ModelDomain& domain, int motors) {
  int outside = 0;
  double pwm_low = std::numeric_limits<double>::infinity(), pwm_high = -pwm_low;
  double volt_low = pwm_low, volt_high = -pwm_low;
  for (const Block& block : blocks) {
    bool out = false;
    for (int k = 0; k < motors; ++k) {
      out |= !domain.contains(block.pwm_us[k], block.voltage_v);
      pwm_low = std::min(pwm_low, block.pwm_us[k]);
      pwm_high = std::max(pwm_high, block.pwm_us[k]);
    }
    volt_low = std::min(volt_low, block.voltage_v);
    volt_high = std::max(volt_high, block.voltage_v);
    outside += out;
  }
  if (blocks.empty() || 2 * outside <= static_cast<int>(blocks.size())) return std::nullopt;
  const bool in_the_box = volt_low >= domain.voltage_min_v && volt_high <= domain.voltage_max_v &&
                          pwm_low >= domain.pwm_min_us && pwm_high <= domain.pwm_max_us;
  // Inside the box yet outside the domain: the bench logged other voltages at these pulse widths
  // (a battery's sag under load), which is what the line must name.
  const auto [covered_low, covered_high] = domain.voltageRange(0.5 * (pwm_low + pwm_high));
  const std::string volts = formatPrintf("%.2f", domain.voltage_min_v) + "-" + formatPrintf("%.2f", domain.voltage_max_v) + " V";
  const std::string pulses = formatPrintf("%.0f", domain.pwm_min_us) + "-" + formatPrintf("%.0f", domain.pwm_max_us) + " us";
  const std::string where =
      in_the_box ? "inside the model's box (" + volts + ", " + pulses + "), but at " +
                       formatPrintf("%.0f", 0.5 * (pwm_low + pwm_high)) + " us the bench logged only " +
                       formatPrintf("%.2f", covered_low) + "-" + formatPrintf("%.2f", covered_high) + " V"
                 : "the model covers " + volts + " and " + pulses;
  return std::to_string(outside) + " of " + std::to_string(blocks.size()) +
         " blocks lie outside the model's domain: the flights' battery reads " + formatPrintf("%.2f", volt_low) + "-" +
         formatPrintf("%.2f", volt_high) + " V and their pulse widths " + formatPrintf("%.0f", pwm_low) + "-" +
         formatPrintf("%.0f", pwm_high) + " us, " + where + " (outside: " + outsideDomainName(domain.outside) +
         "): is this the right model for this vehicle and battery?";
}

}  // namespace detail
}  // namespace gap
}  // namespace propulsion_estimator
