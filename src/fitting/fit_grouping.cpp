#include "propulsion_estimator/fitting/fit_grouping.h"

#include "propulsion_estimator/common/number_format.h"

namespace propulsion_estimator {
namespace fitting {

Grouping resolveGrouping(const BenchDataset& data, FitGrouping requested) {
  Grouping grouping;
  const int voltage_levels = static_cast<int>(data.voltage_levels.size());
  grouping.chosen_automatically = requested == FitGrouping::kAuto;
  // Voltage levels when holding one out leaves at least two to fit a voltage term.
  grouping.kind = requested != FitGrouping::kAuto ? requested
                  : voltage_levels >= 3          ? FitGrouping::kVoltageLevel
                                                 : FitGrouping::kPwmLevel;
  switch (grouping.kind) {
    case FitGrouping::kVoltageLevel:
      grouping.group_of_row = data.voltage_level;
      for (const Level& level : data.voltage_levels) {
        grouping.group_names.push_back(formatPrintf("the %.2f V level", level.centre));
      }
      grouping.description = "leave one voltage level out (" + std::to_string(grouping.groups()) + " levels, " +
                             formatPrintf("%.2f", data.voltage_levels.front().centre) + " to " +
                             formatPrintf("%.2f V", data.voltage_levels.back().centre) + ")";
      break;
    case FitGrouping::kPwmLevel:
      grouping.group_of_row = data.pwm_level;
      for (const Level& level : data.pwm_levels) {
        grouping.group_names.push_back(formatPrintf("the %.0f us level", level.centre));
      }
      grouping.description = "leave one PWM level out (" + std::to_string(grouping.groups()) + " levels, " +
                             formatPrintf("%.0f", data.pwm_levels.front().centre) + " to " +
                             formatPrintf("%.0f us", data.pwm_levels.back().centre) + ")";
      if (voltage_levels == 2) grouping.description += "; 2 voltage levels only, so the voltage degree is at most 1";
      break;
    default:
      grouping.group_of_row = data.log;
      grouping.group_names = data.sources;
      grouping.description = "leave one log out (" + std::to_string(grouping.groups()) + " logs)";
      break;
  }
  return grouping;
}

std::string groupingFlag(const Grouping& grouping) {
  const char* kind = grouping.kind == FitGrouping::kVoltageLevel ? "voltage"
                     : grouping.kind == FitGrouping::kPwmLevel   ? "pwm"
                                                                 : "log";
  return grouping.chosen_automatically ? std::string("--group-by auto (by ") + kind + ")"
                                       : std::string("--group-by ") + kind;
}

}  // namespace fitting
}  // namespace propulsion_estimator
