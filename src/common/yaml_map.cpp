#include "propulsion_estimator/common/yaml_map.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include "propulsion_estimator/common/name_list.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/text_file.h"

namespace propulsion_estimator {
namespace {

// A scalar this long is shown by its start: a CSV or a text given as a YAML file reads as one
// plain scalar, the whole file.
constexpr std::size_t kLongestScalarShown = 60;

std::string describe(const YAML::Node& value) {
  if (value.IsScalar() && value.Scalar().size() > kLongestScalarShown) {
    return "'" + value.Scalar().substr(0, kLongestScalarShown) + "...' (a text of " +
           std::to_string(value.Scalar().size()) + " characters)";
  }
  if (value.IsScalar()) return "'" + value.Scalar() + "'";
  if (value.IsSequence()) return "a list";
  if (value.IsMap()) return "a mapping";
  return "nothing";
}

std::string lineOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.line >= 0 ? std::to_string(mark.line + 1) : "?";
}

/// Refuses a mapping that gives a key twice (yaml-cpp keeps both and looks up the first), as
/// "<source>:<line>: <key.path>: key given twice (first on line <n>)". Reads the parser's events,
/// so that aliases are not expanded.
class DuplicateKeyCheck : public YAML::EventHandler {
 public:
  explicit DuplicateKeyCheck(std::string source) : source_(std::move(source)) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override { node(); }
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override { node(); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string& value) override {
    if (!frames_.empty() && frames_.back().is_map && frames_.back().expecting_key) {
      Frame& map = frames_.back();
      const auto [first, inserted] = map.key_lines.emplace(value, mark.line + 1);
      if (!inserted) {
        throw ConfigError(source_ + ":" + std::to_string(mark.line + 1) + ": " + childPath(map, value) +
                          ": key given twice (first on line " + std::to_string(first->second) + ")");
      }
      map.key = value;
    }
    node();
  }
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    start(false);
  }
  void OnSequenceEnd() override { end(); }
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    start(true);
  }
  void OnMapEnd() override { end(); }

 private:
  struct Frame {
    bool is_map = false;
    bool expecting_key = true;  // a map's next node is a key, else that key's value
    std::size_t index = 0;      // a sequence's next element
    std::string key;            // a map's current key
    std::string path;
    std::map<std::string, int> key_lines;
  };

  static std::string childPath(const Frame& map, const std::string& key) {
    return map.path.empty() ? key : map.path + "." + key;
  }
  // The path of the node starting now, in the innermost collection.
  std::string nextPath() const {
    if (frames_.empty()) return "";
    const Frame& parent = frames_.back();
    if (!parent.is_map) return parent.path + "[" + std::to_string(parent.index) + "]";
    return parent.expecting_key ? parent.path + ".?" : childPath(parent, parent.key);
  }
  // A whole node (scalar, alias or collection) has been read in the innermost collection.
  void node() {
    if (frames_.empty()) return;
    Frame& parent = frames_.back();
    if (parent.is_map) {
      if (!parent.expecting_key) parent.key.clear();
      parent.expecting_key = !parent.expecting_key;
    } else {
      ++parent.index;
    }
  }
  void start(bool is_map) {
    Frame frame;
    frame.is_map = is_map;
    frame.path = nextPath();
    frames_.push_back(std::move(frame));
  }
  void end() {
    frames_.pop_back();
    node();
  }

  std::string source_;
  std::vector<Frame> frames_;
};

}  // namespace

YamlMap::YamlMap(const YAML::Node& node, std::string source, std::string path)
    : node_(node), source_(std::move(source)), path_(std::move(path)) {
  if (!node_.IsMap()) {
    throw ConfigError(source_ + ":" + lineOf(node_) + ": " + (path_.empty() ? "document" : path_) +
                      ": expected a mapping, got " + describe(node_));
  }
  for (const auto& entry : node_) {
    if (!entry.first.IsScalar()) {
      throw ConfigError(source_ + ":" + lineOf(entry.first) + ": " + (path_.empty() ? "document" : path_) +
                        ": a key must be a name, got " + describe(entry.first));
    }
  }
}

std::string YamlMap::keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

std::string YamlMap::where(const std::string& key) const {
  const YAML::Node value = node_[key];
  return source_ + ":" + lineOf(value.IsDefined() ? value : node_) + ": " + keyPath(key);
}

void YamlMap::fail(const std::string& key, const std::string& problem) const {
  throw ConfigError(where(key) + ": " + problem);
}

void YamlMap::allowOnly(std::initializer_list<const char*> allowed) const {
  allowOnly(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void YamlMap::allowOnly(const std::vector<std::string>& allowed) const {
  for (const auto& entry : node_) {
    const std::string key = entry.first.as<std::string>();
    const bool known = std::find(allowed.begin(), allowed.end(), key) != allowed.end();
    if (!known) {
      throw ConfigError(source_ + ":" + lineOf(entry.first) + ": " + keyPath(key) + ": unknown key (allowed: " +
                        joined(allowed) + ")");
    }
  }
}

bool YamlMap::has(const std::string& key) const { return node_[key].IsDefined() && !node_[key].IsNull(); }

bool YamlMap::isSequence(const std::string& key) const { return has(key) && node_[key].IsSequence(); }

std::vector<std::string> YamlMap::keys() const {
  std::vector<std::string> result;
  for (const auto& entry : node_) result.push_back(entry.first.as<std::string>());
  return result;
}

YAML::Node YamlMap::required(const std::string& key) const {
  const YAML::Node value = node_[key];
  if (!value.IsDefined() || value.IsNull()) {
    throw ConfigError(source_ + ":" + lineOf(node_) + ": " + keyPath(key) + ": missing key");
  }
  return value;
}

double YamlMap::toNumber(const YAML::Node& value, const std::string& key) const {
  if (!value.IsScalar()) fail(key, "expected a number, got " + describe(value));
  double number = 0.0;
  try {
    number = value.as<double>();
  } catch (const YAML::Exception&) {
    fail(key, "expected a number, got " + describe(value));
  }
  if (!std::isfinite(number)) fail(key, "expected a finite number, got " + describe(value));
  return number;
}

double YamlMap::number(const std::string& key) const { return toNumber(required(key), key); }

std::optional<double> YamlMap::optionalNumber(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return number(key);
}

int YamlMap::integer(const std::string& key) const {
  const YAML::Node value = required(key);
  const double number = toNumber(value, key);
  if (number != std::floor(number) || std::fabs(number) > 1e9) fail(key, "expected an integer, got " + describe(value));
  return static_cast<int>(number);
}

bool YamlMap::boolean(const std::string& key) const {
  const YAML::Node value = required(key);
  try {
    if (value.IsScalar()) return value.as<bool>();
  } catch (const YAML::Exception&) {
  }
  fail(key, "expected true or false, got " + describe(value));
}

std::string YamlMap::text(const std::string& key) const {
  const YAML::Node value = required(key);
  if (!value.IsScalar()) fail(key, "expected text, got " + describe(value));
  return value.Scalar();
}

std::optional<std::string> YamlMap::optionalText(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return text(key);
}

std::pair<double, double> YamlMap::range(const std::string& key) const {
  const YAML::Node value = required(key);
  if (!value.IsSequence() || value.size() != 2) fail(key, "expected [min, max], got " + describe(value));
  const double lo = toNumber(value[0], key);
  const double hi = toNumber(value[1], key);
  if (!(lo < hi)) {
    std::ostringstream message;
    message << "empty range [" << lo << ", " << hi << "]";
    fail(key, message.str());
  }
  return {lo, hi};
}

std::vector<double> YamlMap::numbers(const std::string& key) const {
  const YAML::Node value = required(key);
  if (!value.IsSequence()) fail(key, "expected a list of numbers, got " + describe(value));
  std::vector<double> result;
  for (const YAML::Node& item : value) result.push_back(toNumber(item, key));
  return result;
}

std::vector<std::string> YamlMap::texts(const std::string& key) const {
  const YAML::Node value = required(key);
  if (!value.IsSequence()) fail(key, "expected a list of text, got " + describe(value));
  std::vector<std::string> result;
  for (const YAML::Node& item : value) {
    if (!item.IsScalar()) fail(key, "expected a list of text, got " + describe(item) + " in it");
    result.push_back(item.Scalar());
  }
  return result;
}

YamlMap YamlMap::map(const std::string& key) const { return YamlMap(required(key), source_, keyPath(key)); }

std::optional<YamlMap> YamlMap::optionalMap(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return map(key);
}

std::vector<YamlMap> YamlMap::maps(const std::string& key) const {
  const YAML::Node value = required(key);
  if (!value.IsSequence()) fail(key, "expected a list, got " + describe(value));
  std::vector<YamlMap> result;
  for (std::size_t i = 0; i < value.size(); ++i) {
    result.emplace_back(value[i], source_, keyPath(key) + "[" + std::to_string(i) + "]");
  }
  return result;
}

std::string YamlMap::choice(const std::string& key, std::initializer_list<const char*> choices) const {
  const std::string value = text(key);
  for (const char* option : choices) {
    if (value == option) return value;
  }
  fail(key, "'" + value + "' is not one of " + joined(std::vector<std::string>(choices.begin(), choices.end())));
}

YamlMap parseYamlDocument(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  if (!root.IsDefined() || root.IsNull()) throw ConfigError(source + ": the file is empty");
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  DuplicateKeyCheck check(source);
  parser.HandleNextDocument(check);
  return YamlMap(root, source, "");
}

YamlMap loadYamlFile(const std::string& path) { return parseYamlDocument(readTextFile(path), path); }

void throwAtField(const YamlMap& root, const FieldError& error) {
  std::vector<std::string> parts;
  std::istringstream stream(error.field());
  for (std::string part; std::getline(stream, part, '.');) parts.push_back(part);

  // Walk down "a.b[2].c" as far as the document goes; the last part present names the line. The
  // maps walked are kept, never assigned: assigning a YAML::Node writes into the node it refers
  // to, and would rewrite the document itself (a later refusal then named a wrong line).
  std::vector<YamlMap> walked = {root};
  std::string key = parts.empty() ? "" : parts.front();
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    const std::size_t bracket = part.find('[');
    key = part.substr(0, bracket);
    if (i + 1 == parts.size() || !walked.back().has(key)) break;
    if (bracket == std::string::npos) {
      walked.push_back(walked.back().map(key));
      continue;
    }
    const std::vector<YamlMap> items = walked.back().maps(key);
    const std::size_t index = std::stoul(part.substr(bracket + 1));
    if (index >= items.size()) break;
    walked.push_back(items[index]);
  }
  const YamlMap& map = walked.back();
  // where() gives "<source>:<line>: <path.key>"; keep the location, name the field as given.
  const std::string where = map.where(key);
  const std::string suffix = ": " + (map.path().empty() ? key : map.path() + "." + key);
  throw ConfigError(where.substr(0, where.size() - suffix.size()) + ": " + error.field() + ": " + error.problem());
}

}  // namespace propulsion_estimator
