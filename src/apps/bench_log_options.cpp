#include "bench_log_options.h"

#include <utility>

#include "propulsion_estimator/common/config_error.h"

namespace propulsion_estimator {
namespace {

SignPolicy signPolicy(const std::string& text) {
  if (text == "as-logged") return SignPolicy::kAsLogged;
  if (text == "negate") return SignPolicy::kNegate;
  return SignPolicy::kAuto;
}

// "QUANTITY=COLUMN": the quantity and the header column; ConfigError saying what is wrong. The
// command line checks it when parsed and readOptions() reads it, through this one function.
std::pair<BenchColumn, std::string> columnMap(const std::string& map) {
  const std::size_t equals = map.find('=');
  if (equals == std::string::npos) throw ConfigError(map + " is not QUANTITY=COLUMN");
  return {benchColumnFromName(map.substr(0, equals)), map.substr(equals + 1)};
}

}  // namespace

void BenchLogOptions::addTo(CLI::App& app) {
  const auto signs = CLI::IsMember({"auto", "as-logged", "negate"});
  app.add_option("--thrust-sign", thrust_sign_,
                 "Thrust sign in Tyto/RCbenchmark logs: auto (negate a column logged negative, refuse mixed signs), "
                 "as-logged, negate")
      ->check(signs)
      ->capture_default_str();
  app.add_option("--current-sign", current_sign_, "Current and power sign, as --thrust-sign")
      ->check(signs)
      ->capture_default_str();
  app.add_option("--map", maps_,
                 "QUANTITY=COLUMN: take a Tyto/RCbenchmark quantity from this header column, e.g. "
                 "rpm='Motor Optical Speed (RPM)' or motor_temp_c='Temp 1 (\xC2\xBA"
                 "C)' (repeatable)")
      ->check(CLI::Validator(
          [](std::string& map) -> std::string {
            try {
              columnMap(map);
            } catch (const ConfigError& e) {
              return e.what();
            }
            return "";
          },
          "QUANTITY=COLUMN"));
  app.add_option("--decimal", decimal_, "Decimal separator of ';'-separated logs: auto, point, comma")
      ->check(CLI::IsMember({"auto", "point", "comma"}))
      ->capture_default_str();
}

BenchReadOptions BenchLogOptions::readOptions() const {
  BenchReadOptions options;
  options.thrust_sign = signPolicy(thrust_sign_);
  options.current_sign = signPolicy(current_sign_);
  options.decimal = decimal_ == "point"   ? DecimalSeparator::kPoint
                    : decimal_ == "comma" ? DecimalSeparator::kComma
                                          : DecimalSeparator::kAuto;
  for (const std::string& map : maps_) {
    const auto [column, header] = columnMap(map);
    options.columns[column] = header;
  }
  return options;
}

std::vector<BenchLog> readBenchLogs(const std::vector<std::string>& arguments, const BenchReadOptions& options) {
  std::vector<BenchLog> logs;
  for (const BenchLogFile& file : expandBenchLogPaths(arguments)) {
    logs.push_back(readBenchLog(file.path, options));
    for (const std::string& argument : file.also_named_by) {
      logs.back().notes.push_back("named again by the argument " + argument + ": read once");
    }
  }
  return logs;
}

}  // namespace propulsion_estimator
