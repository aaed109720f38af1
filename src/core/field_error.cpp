#include "propulsion_estimator/core/field_error.h"

#include <sstream>

#include "propulsion_estimator/core/number_format.h"

namespace propulsion_estimator {

void requireWithin(const std::string& field, double value, double lo, double hi, const std::string& unit) {
  if (!(value >= lo && value <= hi)) {
    throw FieldError(field, formatNumber(value) + " is outside " + formatNumber(lo) + ".." + formatNumber(hi) + unit);
  }
}

void requirePositive(const std::string& field, double value, double hi, const std::string& unit) {
  if (!(value > 0.0 && value <= hi)) {
    throw FieldError(field, formatNumber(value) + " is outside 0.." + formatNumber(hi) + unit + " (must be positive)");
  }
}

void throwAtField(const YamlMap& root, const FieldError& error) {
  std::vector<std::string> parts;
  std::istringstream stream(error.field());
  for (std::string part; std::getline(stream, part, '.');) parts.push_back(part);

  // Walk down "a.b[2].c" as far as the document goes; the last part present names the line.
  YamlMap map = root;
  std::string key = parts.empty() ? "" : parts.front();
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    const std::size_t bracket = part.find('[');
    key = part.substr(0, bracket);
    if (i + 1 == parts.size() || !map.has(key)) break;
    if (bracket == std::string::npos) {
      map = map.map(key);
      continue;
    }
    const std::vector<YamlMap> items = map.maps(key);
    const std::size_t index = std::stoul(part.substr(bracket + 1));
    if (index >= items.size()) break;
    map = items[index];
  }
  // where() gives "<source>:<line>: <path.key>"; keep the location, name the field as given.
  const std::string where = map.where(key);
  const std::string suffix = ": " + (map.path().empty() ? key : map.path() + "." + key);
  throw ConfigError(where.substr(0, where.size() - suffix.size()) + ": " + error.field() + ": " + error.problem());
}

}  // namespace propulsion_estimator
