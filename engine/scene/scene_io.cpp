#include "engine/scene/scene_io.h"

#include <algorithm>
#include <cctype>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/scene/config_tree.h"
#include "engine/scene/detail/overrides.h"
#include "engine/scene/detail/scene_reader.h"
#include "engine/scene/detail/scene_writer.h"
#include "engine/scene/detail/schema_builder.h"
#include "engine/scene/scene_fields.h"

namespace sky {
namespace {

ConfigNode sceneTree(const Scene& scene) {
  Scene copy = scene;  // the description takes mutable references (the reader fills them)
  ConfigNode root = ConfigNode::makeMap({});
  detail::SceneWriter::write(root, copy);
  return root;
}

}  // namespace

ConfigFormat formatForPath(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".yaml" || ext == ".yml") return ConfigFormat::Yaml;
  if (ext == ".json") return ConfigFormat::Json;
  inputError(path.string() + ": unsupported scene file extension " +
             (ext.empty() ? std::string("(none)") : "'" + path.extension().string() + "'") +
             ": use .yaml, .yml or .json");
}

Scene loadSceneText(std::string_view text, ConfigFormat format, const std::string& sourceName,
                    const std::vector<std::string>& overrides) {
  ConfigNode root = format == ConfigFormat::Yaml ? parseYamlTree(text, sourceName)
                                                 : parseJsonTree(text, sourceName);
  for (const std::string& o : overrides) detail::applyOverride(root, o);
  Scene scene;
  detail::SceneReader::read(root, "", scene);
  return scene;
}

namespace {

// Nothing but blank lines and (YAML) comments: a file that says nothing, more likely a
// truncated or wrong file than a wish for the format's defaults.
bool saysNothing(std::string_view text, ConfigFormat format) {
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    const size_t first = line.find_first_not_of(" \t\r");
    if (first != std::string_view::npos && !(format == ConfigFormat::Yaml && line[first] == '#'))
      return false;
    start = end + 1;
  }
  return true;
}

}  // namespace

// The largest scene file read: the shipped ones are under 20 KB, and a scene written by a
// program (a dataset's thousands of views in one file) stays far below this. A YAML parser's
// tree costs tens of times the text, so without a cap a symlink to a huge file, or a
// generated one gone wrong, took all memory before the first error.
constexpr std::uintmax_t kMaxSceneFileBytes = 16u << 20;

Scene loadSceneFile(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  ConfigFormat format = formatForPath(path);
  const std::string text = readTextFile(path, kMaxSceneFileBytes);
  if (saysNothing(text, format))
    inputError(path.string() +
               ": the scene file is empty; for the built-in default scene give no scene file, "
               "for the format's defaults write {}");
  Scene scene = loadSceneText(text, format, path.string(), overrides);
  scene.baseDir = path.parent_path();
  return scene;
}

std::string sceneKeySource(const std::filesystem::path& sceneFile,
                           const std::vector<std::string>& overrides, std::string_view keyPath) {
  const std::string prefix = std::string(keyPath) + "=";
  for (auto it = overrides.rbegin(); it != overrides.rend(); ++it)
    if (it->rfind(prefix, 0) == 0) return "--set " + std::string(keyPath);
  if (sceneFile.empty()) return "";
  try {
    const std::string text = readTextFile(sceneFile, kMaxSceneFileBytes);
    const ConfigNode root = formatForPath(sceneFile) == ConfigFormat::Yaml
                                ? parseYamlTree(text, sceneFile.string())
                                : parseJsonTree(text, sceneFile.string());
    const ConfigNode* node = &root;
    for (size_t start = 0; node && start <= keyPath.size();) {
      const size_t dot = std::min(keyPath.find('.', start), keyPath.size());
      node = node->isMap() ? node->find(keyPath.substr(start, dot - start)) : nullptr;
      start = dot + 1;
    }
    return node ? node->pos.str() : "";
  } catch (const Error&) {
    return "";  // the file loaded once; if it changed since, say nothing rather than wrong
  }
}

std::string writeScene(const Scene& scene, ConfigFormat format) {
  ConfigNode root = sceneTree(scene);
  return format == ConfigFormat::Yaml ? detail::toYamlText(root) : detail::toJsonText(root);
}

std::string sceneJsonSchema() {
  return detail::SchemaBuilder::documentText<Scene>(
      "skylayers scene",
      "A skylayers scene file (YAML or JSON). Every key is optional; absent keys take "
      "the defaults shown.");
}

nlohmann::json sceneToJson(const Scene& scene) {
  return detail::toJsonValue(sceneTree(scene));
}

}  // namespace sky
