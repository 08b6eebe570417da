#pragma once
// Builds the JSON Schema (draft 2020-12) of the scene format from the field description,
// with the defaults taken from the settings it walks.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "engine/scene/field_rules.h"
#include "engine/scene/iso_time.h"
#include "engine/scene/scene.h"
#include "engine/scene/detail/scene_writer.h"

namespace sky::detail {

// The pattern the schema gives for times. IsoTime::parse is the real rule; a test checks
// that the two agree on a list of good and bad times.
extern const char* const kIsoTimePattern;

class SchemaBuilder {
public:
  using Json = nlohmann::ordered_json;

  // An object schema for `settings`, with its properties described and defaults filled.
  template <class T>
  static Json objectSchema(T& settings, std::string_view description) {
    Json schema = emptyObject(description);
    SchemaBuilder builder(schema);
    describe(builder, settings);
    return schema;
  }
  // A whole schema file's text (draft 2020-12) for files of T: its title, then its body.
  template <class T>
  static std::string documentText(std::string_view title, std::string_view description) {
    T defaults{};
    Json schema = Json::object();
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema";
    schema["title"] = std::string(title);
    // Appended after the header keys so "$schema" and "title" come first in the file (the
    // body held here: a range-for over a temporary's items() dangles).
    Json body = objectSchema(defaults, description);
    for (auto& [key, value] : body.items()) schema[key] = value;
    return schema.dump(2) + "\n";
  }

  template <class T>
  void section(std::string_view key, T& settings, std::string_view description) {
    mSchema["properties"][std::string(key)] = objectSchema(settings, description);
  }

  // An optional section: no defaults (absent means absent), every key required when given.
  template <class T>
  void section(std::string_view key, std::optional<T>&, std::string_view description) {
    T probe{};
    Json s = objectSchema(probe, description);
    Json required = Json::array();
    for (auto& [name, prop] : s["properties"].items()) {
      required.push_back(name);
      prop.erase("default");
    }
    s["required"] = std::move(required);
    mSchema["properties"][std::string(key)] = std::move(s);
  }

  void field(std::string_view key, const int& value, NumberRange range,
             std::string_view description);
  void field(std::string_view key, const double& value, NumberRange range,
             std::string_view description);
  void field(std::string_view key, const std::optional<double>& value, NumberRange range,
             std::string_view description);
  void field(std::string_view key, const glm::vec3& value, NumberRange range,
             std::string_view description);
  void field(std::string_view key, const glm::dvec2& value, NumberRange range,
             std::string_view description);
  void field(std::string_view key, const bool& value, std::string_view description);
  void field(std::string_view key, const std::string& value, const TextRule& rule,
             std::string_view description);
  void field(std::string_view key, const std::vector<std::string>& values, const TextRule& rule,
             std::string_view description);
  void field(std::string_view key, const std::optional<glm::dvec2>& value, NumberRange range,
             std::string_view description);
  void field(std::string_view key, const TimeSettings& value, std::string_view description);
  void field(std::string_view key, const std::optional<IsoTime>& value, std::string_view);
  template <SceneEnum E>
  void field(std::string_view key, const E& value, std::string_view description) {
    std::vector<std::string_view> names;
    for (const EnumName<E>& n : enumNames(E{})) names.emplace_back(n.name);
    choice(key, enumName(value), names, description);
  }
  template <SceneEnum E>
  void field(std::string_view key, const std::vector<E>&, std::string_view description) {
    std::vector<std::string_view> names;
    for (const EnumName<E>& n : enumNames(E{})) names.emplace_back(n.name);
    choice(key, enumNames(E{})[0].name, names, description);
    listOfThat(key, description);
  }
  template <class T>
  void list(std::string_view key, const std::vector<T>& items, ListRule rule,
            std::string_view description) {
    T probe{};
    Json item = objectSchema(probe, "one item");
    Json required = Json::array();
    for (auto& [name, _] : item["properties"].items()) required.push_back(name);
    item["required"] = std::move(required);
    for (auto& [name, prop] : item["properties"].items()) prop.erase("default");
    Json s = Json::object();
    s["description"] = std::string(description);
    s["type"] = "array";
    s["items"] = std::move(item);
    s["minItems"] = rule.minItems;
    if (rule.maxItems) s["maxItems"] = rule.maxItems;
    s["default"] = listDefault(items);
    mSchema["properties"][std::string(key)] = std::move(s);
  }
  void bothOrNeither(std::string_view a, std::string_view b);
  // Cross-field rules are checked by the reader only (described in the field texts).
  void check(std::string_view, bool, std::string_view) {}

private:
  explicit SchemaBuilder(Json& schema) : mSchema(schema) {}
  // Turns the property `key` just described into a non-empty list of such values.
  void listOfThat(std::string_view key, std::string_view description);
  // The items as the writer prints them, so the schema default is what `validate` shows.
  template <class T>
  static Json listDefault(const std::vector<T>& items);
  static Json emptyObject(std::string_view description);
  // A string that is one of `names`, as the pattern ^(a|b|c)$.
  void choice(std::string_view key, const char* value, const std::vector<std::string_view>& names,
              std::string_view description);

  Json& mSchema;
};

// A written map as ordered JSON (keys in the order the description gives them).
SchemaBuilder::Json orderedJson(const ConfigNode& map);

template <class T>
SchemaBuilder::Json SchemaBuilder::listDefault(const std::vector<T>& items) {
  Json out = Json::array();
  for (T item : items) {
    ConfigNode map = ConfigNode::makeMap({});
    SceneWriter::write(map, item);
    out.push_back(orderedJson(map));
  }
  return out;
}

}  // namespace sky::detail
