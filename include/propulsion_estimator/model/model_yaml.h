#pragma once

#include <string>

#include "propulsion_estimator/model/propulsion_model.h"

namespace propulsion_estimator {

/// @file
/// Reader and writer of the model file (one ESC-motor-propeller combination; schema in docs/model_files.md).
/// Both throw ConfigError with one line naming the file, the line, the key and the value.

/// Parses and validates a model: structure, types, units, finiteness, the values of every output
/// on a grid over the domain (model_validation.h), and the optional `effects:` section
/// (effects::ModelEffects::validate(); an air_density effect needs the metadata's bench air).
/// `source` names the text in messages.
PropulsionModel parseModelYaml(const std::string& text, const std::string& source);
/// Reads and parses the model file `path`: InputError when it cannot be read, else as parseModelYaml.
PropulsionModel loadModelFile(const std::string& path);

/// Writes a model that parseModelYaml reads back to the same surfaces (coefficients are written
/// with as many digits as they need to round-trip). `comment` goes on top of the file.
std::string modelToYaml(const PropulsionModel& model, const std::string& comment = "");
/// Writes modelToYaml's text to `path`; InputError naming it when it cannot be written.
void saveModelFile(const PropulsionModel& model, const std::string& path, const std::string& comment = "");

/// 16 hex digits identifying the surfaces, domain, metadata and effects of a model (a hash of
/// what modelToYaml writes), whatever file it was read from: a tare is valid only with its model,
/// and a corrected model (effects added) estimates another empty mass than the plain one.
std::string modelFingerprint(const PropulsionModel& model);

}  // namespace propulsion_estimator
