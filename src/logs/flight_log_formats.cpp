#include "propulsion_estimator/logs/flight_log_formats.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/data_error.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/text_file.h"

namespace propulsion_estimator {

void FlightLogOptions::validate(const std::string& what) const {
  if (motors < 1 || motors > kMaxMotors) {
    throw ConfigError(what + ": " + std::to_string(motors) + " motors, expected 1.." + std::to_string(kMaxMotors));
  }
  for (const auto& [name, source] : sources) {
    const std::vector<std::string>& names = flightSignalNames();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      throw ConfigError(what + ": '" + name + "' is not a signal (one of " + joined(names) + ")");
    }
    if (source.empty()) throw ConfigError(what + ": " + name + ": an empty source");
  }
  const bool min_given = !std::isnan(pwm_min_us);
  if (min_given != !std::isnan(pwm_max_us)) throw ConfigError(what + ": a PWM range needs both its ends");
  if (min_given && !(pwm_min_us >= 500.0 && pwm_max_us <= 2500.0 && pwm_min_us < pwm_max_us)) {
    throw ConfigError(what + ": PWM range " + formatNumber(pwm_min_us) + ".." + formatNumber(pwm_max_us) +
                      " us, expected min < max within 500..2500 us");
  }
}

std::string FlightLogOptions::unusedSourcesNote(const std::string& format) const {
  if (sources.empty()) return "";
  std::vector<std::string> given;
  for (const auto& [name, source] : sources) given.push_back(name + "=" + source);
  return "sources given (" + joined(given) + ") not used: " + format + " is read from its own messages, named above";
}

void FlightLogFormats::add(FlightLogFormat format) {
  if (format.magic.empty()) throw std::invalid_argument("flight-log format " + format.name + ": no magic bytes");
  for (const FlightLogFormat& known : formats_) {
    if (known.name == format.name || known.magic == format.magic) {
      throw std::invalid_argument("flight-log format " + format.name + " added twice");
    }
  }
  formats_.push_back(std::move(format));
}

std::unique_ptr<FlightLogReader> FlightLogFormats::open(const std::string& path) const {
  requireRegularFile(path);
  std::size_t longest = 0;
  for (const FlightLogFormat& format : formats_) longest = std::max(longest, format.magic.size());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot be read");
  std::string head(longest, '\0');
  in.read(head.data(), static_cast<std::streamsize>(longest));
  head.resize(static_cast<std::size_t>(in.gcount()));
  for (const FlightLogFormat& format : formats_) {
    if (head.compare(0, format.magic.size(), format.magic) == 0) return format.open(path);
  }
  if (head.empty()) throw DataError(path + ": empty: not a flight log");
  // A file that ends inside a format's first bytes is that format's log cut short, not a stranger.
  for (const FlightLogFormat& format : formats_) {
    if (head.size() < format.magic.size() && format.magic.compare(0, head.size(), head) == 0) {
      throw DataError(path + ": a " + format.name + " log cut short: it ends after " + std::to_string(head.size()) +
                      (head.size() == 1 ? " byte" : " bytes") + ", within its first " +
                      std::to_string(format.magic.size()) + " (\"" + printableBytes(format.magic) + "\")");
    }
  }
  throw DataError(path + ": not a flight log of a known format (" + joined(names()) + "): it starts with \"" + printableBytes(head) +
                  "\"");
}

std::vector<std::string> FlightLogFormats::names() const {
  std::vector<std::string> names;
  for (const FlightLogFormat& format : formats_) names.push_back(format.name);
  return names;
}

std::string readFlightLogBytes(const std::string& path) {
  requireRegularFile(path);
  return readTextFile(path);
}

std::string withoutLogPath(const std::string& line, const std::string& path) {
  const std::string named = path + ": ";
  return line.rfind(named, 0) == 0 ? line.substr(named.size()) : line;
}

std::string nothingReadLine(const std::string& path, const std::string& nothing, const std::string& refusal) {
  return path + ": " + nothing + (refusal.empty() ? "" : " (" + withoutLogPath(refusal, path) + ")");
}

std::string printableBytes(const std::string& bytes) {
  static const char kHex[] = "0123456789abcdef";
  std::string text;
  for (const char c : bytes) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7f && c != '"' && c != '\\') {
      text += c;
    } else {
      text += std::string("\\x") + kHex[byte >> 4] + kHex[byte & 0xf];
    }
  }
  return text;
}

}  // namespace propulsion_estimator
