#include "propulsion_estimator/estimation/tare_file.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include <yaml-cpp/yaml.h>

#include "propulsion_estimator/common/input_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {

std::optional<TareRecord> loadTareFile(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return std::nullopt;
  const YamlMap root = loadYamlFile(path);
  root.allowOnly({"empty_mass_kg", "model", "model_fingerprint"});
  TareRecord record{root.number("empty_mass_kg"), root.text("model"), root.text("model_fingerprint")};
  if (record.empty_mass_kg <= 0.0) root.fail("empty_mass_kg", "must be positive");
  return record;
}

void saveTareFile(const std::string& path, const TareRecord& record) {
  const std::filesystem::path target(path);
  std::error_code error;
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path(), error);
  const std::string temporary = path + ".tmp";
  {
    char mass[32];
    std::snprintf(mass, sizeof(mass), "%.17g", record.empty_mass_kg);
    YAML::Emitter yaml;
    yaml << YAML::Comment("Written by propulsion_estimator's ~tare service.") << YAML::Newline << YAML::BeginMap
         << YAML::Key << "empty_mass_kg" << YAML::Value << mass << YAML::Key << "model" << YAML::Value
         << record.model << YAML::Key << "model_fingerprint" << YAML::Value << record.model_fingerprint << YAML::EndMap;
    writeTextFile(temporary, std::string(yaml.c_str()) + "\n");
  }
  std::filesystem::rename(temporary, target, error);
  if (error) throw InputError(path + ": cannot write the tare file: " + error.message());
}

void removeTareFile(const std::string& path) {
  std::error_code error;
  std::filesystem::remove(path, error);
}

}  // namespace propulsion_estimator
