#include "propulsion_estimator/onboard/tare_file.h"

#include <filesystem>
#include <system_error>

#include <yaml-cpp/yaml.h>

#include "propulsion_estimator/common/atomic_file.h"
#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/number_format.h"
#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {

TareRecord parseTareFile(const std::string& text, const std::string& source) {
  const YamlMap root = parseYamlDocument(text, source);
  root.allowOnly({"empty_mass_kg", "model", "model_fingerprint"});
  TareRecord record{root.number("empty_mass_kg"), root.text("model"), root.text("model_fingerprint")};
  if (record.empty_mass_kg <= 0.0) root.fail("empty_mass_kg", "must be positive");
  return record;
}

std::optional<TareRecord> loadTareFile(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return std::nullopt;
  return parseTareFile(readTextFile(path), path);
}

void saveTareFile(const std::string& path, const TareRecord& record) {
  const std::string mass = formatNumber(record.empty_mass_kg);  // reads back to the same double
  YAML::Emitter yaml;
  yaml << YAML::Comment("Written by propulsion_estimator's ~tare service.") << YAML::Newline << YAML::BeginMap
       << YAML::Key << "empty_mass_kg" << YAML::Value << mass << YAML::Key << "model" << YAML::Value << record.model
       << YAML::Key << "model_fingerprint" << YAML::Value << record.model_fingerprint << YAML::EndMap;
  writeFileAtomically(path, std::string(yaml.c_str()) + "\n", "tare file");
}

std::vector<std::string> removeStaleTareTemporaries(const std::string& path) { return removeStaleTemporaries(path); }

bool removeTareFile(const std::string& path) {
  std::error_code error;
  const bool removed = std::filesystem::remove(path, error);
  if (error) throw InputError(path + ": cannot remove the tare file: " + error.message());
  return removed;
}

TareAtStart loadTareAtStart(const std::string& path, long long unix_time) {
  try {
    return {loadTareFile(path), ""};
  } catch (const ConfigError& e) {
    std::string refusal = std::string("refused: ") + e.what() + "; started without the tare";
    try {
      refusal += ", the file moved to " + setAsideTareFile(path, unix_time);
    } catch (const InputError& moved) {
      refusal += std::string("; ") + moved.what();
    }
    return {std::nullopt, refusal};
  } catch (const InputError& e) {
    return {std::nullopt, std::string("refused: ") + e.what() + "; started without the tare"};
  }
}

std::string setAsideTareFile(const std::string& path, long long unix_time) {
  const std::string aside = path + ".bad-" + std::to_string(unix_time);
  std::error_code error;
  std::filesystem::rename(path, aside, error);
  if (error) throw InputError(path + ": cannot move the tare file to " + aside + ": " + error.message());
  return aside;
}

}  // namespace propulsion_estimator
