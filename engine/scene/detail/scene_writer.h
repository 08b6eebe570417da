#pragma once
// Turns settings back into a ConfigNode tree through the field description, and prints
// trees as YAML or JSON text. Numbers are printed shortest-round-trip, so reading the text
// back gives identical settings.
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "engine/scene/config_tree.h"
#include "engine/scene/field_rules.h"
#include "engine/scene/iso_time.h"
#include "engine/scene/scene.h"

namespace sky::detail {

class SceneWriter {
public:
  // Appends the fields of `settings` to `map` (a Map node).
  template <class T>
  static void write(ConfigNode& map, T& settings) {
    SceneWriter writer(map);
    describe(writer, settings);
    writer.checkPairs();
  }

  template <class T>
  void section(std::string_view key, T& settings, std::string_view) {
    write(mMap.add(std::string(key), {}, ConfigNode::makeMap({})), settings);
  }

  // An optional section is written only when it has a value.
  template <class T>
  void section(std::string_view key, std::optional<T>& settings, std::string_view) {
    if (settings) write(mMap.add(std::string(key), {}, ConfigNode::makeMap({})), *settings);
  }

  void field(std::string_view key, const int& value, NumberRange, std::string_view);
  void field(std::string_view key, const double& value, NumberRange, std::string_view);
  void field(std::string_view key, const std::optional<double>& value, NumberRange,
             std::string_view);
  void field(std::string_view key, const glm::vec3& value, NumberRange, std::string_view);
  void field(std::string_view key, const glm::dvec2& value, NumberRange, std::string_view);
  void field(std::string_view key, const bool& value, std::string_view);
  void field(std::string_view key, const std::string& value, const TextRule&, std::string_view);
  void field(std::string_view key, const std::vector<std::string>& values, const TextRule&,
             std::string_view);
  void field(std::string_view key, const std::optional<glm::dvec2>& value, NumberRange range,
             std::string_view description) {
    if (value) field(key, *value, range, description);  // absent stays absent
  }
  void field(std::string_view key, const TimeSettings& value, std::string_view);
  void field(std::string_view key, const std::optional<IsoTime>& value, std::string_view);
  template <SceneEnum E>
  void field(std::string_view key, const E& value, std::string_view) {
    choice(key, enumName(value));
  }
  template <SceneEnum E>
  void field(std::string_view key, const std::vector<E>& values, std::string_view) {
    std::vector<std::string> names;
    for (const E& v : values) names.emplace_back(enumName(v));
    if (!values.empty()) field(key, names, TextRule{}, "");
  }
  template <class T>
  void list(std::string_view key, const std::vector<T>& items, ListRule, std::string_view) {
    ConfigNode seq = ConfigNode::makeSequence({});
    for (T item : items) {
      ConfigNode map = ConfigNode::makeMap({});
      write(map, item);
      seq.children.push_back(std::move(map));
    }
    mMap.add(std::string(key), {}, std::move(seq));
  }
  // Checked once the section is complete (the pair may be described in any order).
  void bothOrNeither(std::string_view a, std::string_view b) { mPairs.emplace_back(a, b); }
  // Cross-field rules are checked by the reader only (described in the field texts).
  void check(std::string_view, bool, std::string_view) {}

private:
  explicit SceneWriter(ConfigNode& map) : mMap(map) {}
  void checkPairs() const;
  void choice(std::string_view key, const char* name);

  ConfigNode& mMap;
  std::vector<std::pair<std::string, std::string>> mPairs;
};

// Block-style YAML (flow lists for colours, block lists of maps), strings always
// double-quoted.
std::string toYamlText(const ConfigNode& root);
// Two-space indented JSON, lists of scalars on one line.
std::string toJsonText(const ConfigNode& root);
// A JSON value (integers stay integers).
nlohmann::json toJsonValue(const ConfigNode& node);

}  // namespace sky::detail
