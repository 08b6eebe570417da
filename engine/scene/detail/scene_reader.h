#pragma once
// Strict typed read of a ConfigNode tree through the field description (scene_fields.h).
// Any unknown key, wrong type or out-of-range value throws sky::Error(BadInput) as
// "<file>:<line>:<col>: <key.path>: <what>".
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/scene/config_tree.h"
#include "engine/scene/field_rules.h"
#include "engine/scene/iso_time.h"
#include "engine/scene/scene.h"

namespace sky::detail {

// Lists a section's keys (the reader checks a map against them before reading it).
class KeyCollector {
public:
  std::vector<std::string> keys;

  template <class T, class... Rest>
  void section(std::string_view key, T&, Rest&&...) {
    keys.emplace_back(key);
  }
  template <class T, class... Rest>
  void field(std::string_view key, T&, Rest&&...) {
    keys.emplace_back(key);
  }
  template <class T, class... Rest>
  void list(std::string_view key, T&, Rest&&...) {
    keys.emplace_back(key);
  }
  void bothOrNeither(std::string_view, std::string_view) {}
  void check(std::string_view, bool, std::string_view) {}
};

class SceneReader {
public:
  // `map` must outlive the reader; `path` is the key path of the map ("" at the top).
  SceneReader(const ConfigNode& map, std::string path) : mMap(map), mPath(std::move(path)) {}

  // Reads a whole section: unknown keys first (in document order), then every field.
  template <class T>
  static void read(const ConfigNode& map, const std::string& path, T& settings) {
    KeyCollector known;
    describe(known, settings);
    checkKeys(map, path, known.keys);
    SceneReader reader(map, path);
    describe(reader, settings);
  }

  template <class T>
  void section(std::string_view key, T& settings, std::string_view) {
    const ConfigNode* node = mMap.find(key);
    if (!node) return;
    std::string path = childPath(key);
    if (!node->isMap())
      fail(*node, path, "expected a map of settings, got " + node->describeKind());
    // `camera: {}` says nothing, like `camera:`; more likely keys lost on the way than a wish
    // (docs/scene-format.md, Strictness). Only the file itself may be {}.
    if (node->children.empty())
      fail(*node, path, "an empty section; give its keys, or leave it out for its defaults");
    read(*node, path, settings);
  }

  // A section the scene may leave out (absent: no value, no defaults). When given it must give
  // every key: half a region filled in from defaults is more likely a mistake than a wish.
  template <class T>
  void section(std::string_view key, std::optional<T>& settings, std::string_view) {
    const ConfigNode* node = mMap.find(key);
    if (!node) return;
    std::string path = childPath(key);
    if (!node->isMap())
      fail(*node, path, "expected a map of settings, got " + node->describeKind());
    KeyCollector known;
    T value{};
    describe(known, value);
    checkKeys(*node, path, known.keys);
    requireAll(*node, path, known.keys);
    read(*node, path, value);
    settings = value;
  }

  void field(std::string_view key, int& value, NumberRange range, std::string_view);
  void field(std::string_view key, double& value, NumberRange range, std::string_view);
  void field(std::string_view key, std::optional<double>& value, NumberRange range,
             std::string_view);
  void field(std::string_view key, glm::vec3& value, NumberRange range, std::string_view);
  void field(std::string_view key, glm::dvec2& value, NumberRange range, std::string_view);
  void field(std::string_view key, bool& value, std::string_view);
  void field(std::string_view key, std::string& value, const TextRule& rule, std::string_view);
  // A list of strings, each by the rule; a list of numbers' pair [from, to] that may be absent.
  void field(std::string_view key, std::vector<std::string>& values, const TextRule& rule,
             std::string_view);
  void field(std::string_view key, std::optional<glm::dvec2>& value, NumberRange range,
             std::string_view);
  void field(std::string_view key, TimeSettings& value, std::string_view);
  void field(std::string_view key, std::optional<IsoTime>& value, std::string_view);
  // A choice: one of the names in E's table (field_rules.h).
  template <SceneEnum E>
  void field(std::string_view key, E& value, std::string_view) {
    const ConfigNode* node = mMap.find(key);
    if (!node) return;
    std::vector<std::string_view> names;
    for (const EnumName<E>& n : enumNames(E{})) names.emplace_back(n.name);
    value = *enumValue<E>(names[choice(*node, childPath(key), names)]);
  }
  // A list of choices, each one of the names in E's table.
  template <SceneEnum E>
  void field(std::string_view key, std::vector<E>& values, std::string_view) {
    const ConfigNode* node = mMap.find(key);
    if (!node) return;
    const std::string path = childPath(key);
    std::vector<std::string_view> names;
    for (const EnumName<E>& n : enumNames(E{})) names.emplace_back(n.name);
    const std::vector<const ConfigNode*> items = sequenceItems(*node, path, "names");
    values.clear();
    for (size_t i = 0; i < items.size(); ++i)
      values.push_back(
          *enumValue<E>(names[choice(*items[i], path + "[" + std::to_string(i) + "]", names)]));
  }
  void bothOrNeither(std::string_view a, std::string_view b);
  // A rule across fields, checked after they are read: fails at `key` (or at this map when
  // the key is absent) with "<key.path>: <what>".
  void check(std::string_view key, bool ok, std::string_view what);

  // A list of maps: each item must give every key of T (a keyframe with a colour missing
  // is more likely a mistake than a wish for black), and rule.increasingKey must increase.
  template <class T>
  void list(std::string_view key, std::vector<T>& items, ListRule rule, std::string_view) {
    const ConfigNode* node = mMap.find(key);
    if (!node) return;
    std::string path = childPath(key);
    checkList(*node, path, rule);
    KeyCollector known;
    T probe{};
    describe(known, probe);
    std::vector<T> result;
    for (size_t i = 0; i < node->children.size(); ++i) {
      const ConfigNode& item = node->children[i];
      std::string itemPath = path + "[" + std::to_string(i) + "]";
      checkKeys(item, itemPath, known.keys);  // a misspelt key first: "did you mean ..."
      requireAll(item, itemPath, known.keys);
      T value{};
      read(item, itemPath, value);
      result.push_back(value);
    }
    checkIncreasing(*node, path, rule);
    items = std::move(result);
  }

private:
  static void checkKeys(const ConfigNode& map, const std::string& path,
                        const std::vector<std::string>& known);
  static void checkList(const ConfigNode& list, const std::string& path, const ListRule& rule);
  static void requireAll(const ConfigNode& map, const std::string& path,
                         const std::vector<std::string>& known);
  static void checkIncreasing(const ConfigNode& list, const std::string& path,
                              const ListRule& rule);
  [[noreturn]] static void fail(const ConfigNode& node, const std::string& path,
                                const std::string& what);
  // The index of the node's text in `names`; fails unless it is one of them.
  static std::string text(const ConfigNode& node, const std::string& path, const TextRule& rule);
  // The items of a list that must not be empty ("expected a list of <what>").
  static std::vector<const ConfigNode*> sequenceItems(const ConfigNode& node,
                                                      const std::string& path,
                                                      const std::string& what);
  static size_t choice(const ConfigNode& node, const std::string& path,
                       const std::vector<std::string_view>& names);
  static double number(const ConfigNode& node, const std::string& path, NumberRange range,
                       const char* expected);
  std::string childPath(std::string_view key) const;

  const ConfigNode& mMap;
  std::string mPath;
};

}  // namespace sky::detail
