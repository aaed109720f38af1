#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "propulsion_estimator/common/field_error.h"

namespace propulsion_estimator {

/// Strict, typed access to one YAML mapping of a configuration file. Every refusal throws
/// ConfigError as "<source>:<line>: <key.path>: <problem>", so that the user sees where to look.
class YamlMap {
 public:
  /// `path` is the dotted key path of this map ("" for the document root).
  YamlMap(const YAML::Node& node, std::string source, std::string path);
  /// A copy refers to the same mapping of the same document.
  YamlMap(const YamlMap&) = default;
  /// Not assignable: assigning a YAML::Node writes into the node it refers to, which would
  /// rewrite the document; keep another YamlMap instead.
  YamlMap& operator=(const YamlMap&) = delete;

  /// Refuses any key not in `allowed`.
  void allowOnly(std::initializer_list<const char*> allowed) const;
  /// The same, for a list built at run time (the effects' names).
  void allowOnly(const std::vector<std::string>& allowed) const;

  bool has(const std::string& key) const;  ///< whether the mapping has `key`
  std::vector<std::string> keys() const;  ///< the mapping's keys, in file order

  double number(const std::string& key) const;  ///< finite
  /// A finite number, or nullopt when the key is absent.
  std::optional<double> optionalNumber(const std::string& key) const;
  int integer(const std::string& key) const;  ///< an integer (a number with a fractional part is refused)
  bool boolean(const std::string& key) const;  ///< true or false
  std::string text(const std::string& key) const;  ///< a scalar as text
  /// A scalar as text, or nullopt when the key is absent.
  std::optional<std::string> optionalText(const std::string& key) const;
  std::pair<double, double> range(const std::string& key) const;  ///< [lo, hi], finite, lo < hi
  std::vector<double> numbers(const std::string& key) const;      ///< a sequence of finite numbers
  std::vector<std::string> texts(const std::string& key) const;  ///< a sequence of scalars, as text
  bool isSequence(const std::string& key) const;  ///< whether `key` holds a sequence (false when absent)
  YamlMap map(const std::string& key) const;  ///< the mapping under `key`
  /// The mapping under `key`, or nullopt when the key is absent.
  std::optional<YamlMap> optionalMap(const std::string& key) const;
  std::vector<YamlMap> maps(const std::string& key) const;  ///< a sequence of mappings
  /// One of `choices`, reported with them when it is not.
  std::string choice(const std::string& key, std::initializer_list<const char*> choices) const;

  /// "<source>:<line>: <path.key>" for messages about a key of this map.
  std::string where(const std::string& key) const;
  /// Throws ConfigError "<source>:<line>: <path.key>: <problem>" (the line of `key`, or of this map).
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

  /// The file or name messages give for the document.
  const std::string& source() const { return source_; }
  /// The dotted key path of this map.
  const std::string& path() const { return path_; }

 private:
  YAML::Node required(const std::string& key) const;
  double toNumber(const YAML::Node& value, const std::string& key) const;
  std::string keyPath(const std::string& key) const;

  YAML::Node node_;
  std::string source_;
  std::string path_;
};

/// Parses a whole document and returns its root mapping; `source` names it in messages. Throws
/// ConfigError for text that is not YAML or is empty, and for a mapping anywhere in the document
/// that gives a key twice: "<source>:<line>: <key.path>: key given twice (first on line <n>)".
YamlMap parseYamlDocument(const std::string& text, const std::string& source);
/// Reads a file and parses it: InputError when it cannot be read, else as parseYamlDocument.
YamlMap loadYamlFile(const std::string& path);
/// Rethrows `error` as "<source>:<line>: <field>: <problem>", with the line of the field in the
/// document whose root is `root` (the line of its nearest present ancestor when it is absent):
/// always throws ConfigError.
[[noreturn]] void throwAtField(const YamlMap& root, const FieldError& error);

/// Runs `config.validate()` and locates a refusal in the document it was read from (ConfigError
/// "<source>:<line>: <field>: <problem>").
template <typename Config>
void validateAt(const YamlMap& root, const Config& config) {
  try {
    config.validate();
  } catch (const FieldError& error) {
    throwAtField(root, error);
  }
}

}  // namespace propulsion_estimator
