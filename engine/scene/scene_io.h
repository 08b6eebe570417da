#pragma once
// Scene files: strict loading from YAML or JSON (same keys, same result), `--set`
// overrides, printing the effective settings, and the JSON Schema of the format.
// The format itself is described once, in engine/scene/scene_fields.h.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene/scene.h"

namespace sky {

enum class ConfigFormat { Yaml, Json };

// Loads a scene file; overrides are "key.path=value" strings applied before validation.
// Throws sky::Error(BadInput) naming the file, line, column and key path.
Scene loadSceneFile(const std::filesystem::path& path,
                    const std::vector<std::string>& overrides = {});
// Same for text already in memory; sourceName is used in error messages.
Scene loadSceneText(std::string_view text, ConfigFormat format, const std::string& sourceName,
                    const std::vector<std::string>& overrides = {});
// Where a scene key got its value, for errors found after loading (a name the OCIO config
// lacks, a file a key names that cannot be read): "--set KEY" when an override gave it,
// else "FILE:LINE:COLUMN" of the value in the scene file, else "" (a default). `keyPath` is
// dotted ("output.display"); `sceneFile` may be empty (the built-in scene).
std::string sceneKeySource(const std::filesystem::path& sceneFile,
                           const std::vector<std::string>& overrides, std::string_view keyPath);
// By extension (.yaml, .yml, .json, any case); anything else is BadInput.
ConfigFormat formatForPath(const std::filesystem::path& path);
// The effective settings (defaults filled in) as file text; loading it gives an identical Scene.
std::string writeScene(const Scene& scene, ConfigFormat format);
// JSON Schema (draft 2020-12) text of the format; configs/schema/scene.schema.json is a copy.
std::string sceneJsonSchema();
// The effective settings as JSON, for render reports.
nlohmann::json sceneToJson(const Scene& scene);

}  // namespace sky
