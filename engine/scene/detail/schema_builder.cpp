#include "engine/scene/detail/schema_builder.h"

#include <cmath>

#include "engine/scene/detail/number_text.h"

namespace sky::detail {

const char* const kIsoTimePattern =
    "^[0-9]{4}-[0-9]{2}-[0-9]{2}[Tt ][0-9]{2}:[0-9]{2}(:[0-9]{2}([.,][0-9]+)?)?"
    "([Zz]|[+-][0-9]{2}(:?[0-9]{2})?)$";

namespace {

using Json = SchemaBuilder::Json;

// Limits and defaults go through the shortest decimal text, so 0.16f appears as 0.16 and
// whole numbers as integers rather than 90.0.
Json numberJson(double v) {
  if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 9.0e15)
    return static_cast<int64_t>(v);
  return *parseNumber(formatDouble(v));
}

Json floatJson(float v) {
  if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 1.0e7f)
    return static_cast<int64_t>(v);
  return *parseNumber(formatFloat(v));
}

Json numberSchema(const char* type, NumberRange range, std::string_view description) {
  Json s = Json::object();
  s["description"] = std::string(description);
  s["type"] = type;
  s["minimum"] = numberJson(range.min);
  s["maximum"] = numberJson(range.max);
  return s;
}

// A list of exactly `items.size()` numbers in `range` (a colour, a [from, to] pair).
Json numberListSchema(NumberRange range, std::string_view description, Json items) {
  Json s = Json::object();
  s["description"] = std::string(description);
  s["type"] = "array";
  Json item = Json::object();
  item["type"] = "number";
  item["minimum"] = numberJson(range.min);
  item["maximum"] = numberJson(range.max);
  s["items"] = std::move(item);
  s["minItems"] = items.size();
  s["maxItems"] = items.size();
  s["default"] = std::move(items);
  return s;
}

}  // namespace

Json SchemaBuilder::emptyObject(std::string_view description) {
  Json s = Json::object();
  s["description"] = std::string(description);
  s["type"] = "object";
  s["additionalProperties"] = false;
  s["properties"] = Json::object();
  return s;
}

void SchemaBuilder::field(std::string_view key, const int& value, NumberRange range,
                          std::string_view description) {
  Json s = numberSchema("integer", range, description);
  s["default"] = value;
  mSchema["properties"][std::string(key)] = std::move(s);
}

void SchemaBuilder::field(std::string_view key, const double& value, NumberRange range,
                          std::string_view description) {
  Json s = numberSchema("number", range, description);
  s["default"] = numberJson(value);
  mSchema["properties"][std::string(key)] = std::move(s);
}

void SchemaBuilder::field(std::string_view key, const std::optional<double>& value,
                          NumberRange range, std::string_view description) {
  Json s = numberSchema("number", range, description);
  if (value) s["default"] = numberJson(*value);
  mSchema["properties"][std::string(key)] = std::move(s);
}

void SchemaBuilder::field(std::string_view key, const glm::vec3& value, NumberRange range,
                          std::string_view description) {
  mSchema["properties"][std::string(key)] =
      numberListSchema(range, description,
                       Json::array({floatJson(value.x), floatJson(value.y), floatJson(value.z)}));
}

void SchemaBuilder::field(std::string_view key, const glm::dvec2& value, NumberRange range,
                          std::string_view description) {
  mSchema["properties"][std::string(key)] =
      numberListSchema(range, description, Json::array({numberJson(value.x), numberJson(value.y)}));
}

void SchemaBuilder::field(std::string_view key, const bool& value, std::string_view description) {
  Json s = Json::object();
  s["description"] = std::string(description);
  s["type"] = "boolean";
  s["default"] = value;
  mSchema["properties"][std::string(key)] = std::move(s);
}

void SchemaBuilder::field(std::string_view key, const std::string& value, const TextRule& rule,
                          std::string_view description) {
  Json s = Json::object();
  s["description"] = std::string(description);
  s["type"] = "string";
  if (rule.minLength) s["minLength"] = rule.minLength;
  if (rule.maxLength) s["maxLength"] = rule.maxLength;
  if (rule.pattern) s["pattern"] = rule.pattern;
  s["default"] = value;
  mSchema["properties"][std::string(key)] = std::move(s);
}

void SchemaBuilder::field(std::string_view key, const std::vector<std::string>& values,
                          const TextRule& rule, std::string_view description) {
  field(key, std::string(), rule, description);
  listOfThat(key, description);
  if (!values.empty()) mSchema["properties"][std::string(key)]["default"] = values;
}

void SchemaBuilder::listOfThat(std::string_view key, std::string_view description) {
  Json item = std::move(mSchema["properties"][std::string(key)]);
  item.erase("default");
  item.erase("description");
  Json s = Json::object();
  s["description"] = std::string(description);
  s["type"] = "array";
  s["items"] = std::move(item);
  s["minItems"] = 1;
  mSchema["properties"][std::string(key)] = std::move(s);
}

void SchemaBuilder::field(std::string_view key, const std::optional<glm::dvec2>& value,
                          NumberRange range, std::string_view description) {
  field(key, value.value_or(glm::dvec2(0.0)), range, description);
  if (!value) mSchema["properties"][std::string(key)].erase("default");  // absent: none
}

void SchemaBuilder::choice(std::string_view key, const char* value,
                           const std::vector<std::string_view>& names,
                           std::string_view description) {
  std::string pattern = "^(";
  for (size_t i = 0; i < names.size(); ++i) pattern += (i ? "|" : "") + std::string(names[i]);
  Json s = Json::object();
  s["description"] = std::string(description);
  s["type"] = "string";
  s["minLength"] = 1;
  s["pattern"] = pattern + ")$";
  s["default"] = value;
  mSchema["properties"][std::string(key)] = std::move(s);
}

Json orderedJson(const ConfigNode& map) {
  Json o = Json::object();
  for (const ConfigNode& c : map.children)
    o[c.key] = c.isMap() ? orderedJson(c) : Json(toJsonValue(c));
  return o;
}

void SchemaBuilder::field(std::string_view key, const TimeSettings& value,
                          std::string_view description) {
  // The reader's rules in schema form: an instant, "START/END/STEP", or the map.
  std::string iso = kIsoTimePattern;
  std::string bare = iso.substr(1, iso.size() - 2);  // without ^ and $
  Json instant = {{"type", "string"}, {"pattern", iso}};
  Json interval = {{"type", "string"}, {"pattern", "^" + bare + "/" + bare + "/[^/]+$"}};
  Json range = {{"type", "object"},
                {"additionalProperties", false},
                {"required", Json::array({"start", "end", "step"})},
                {"properties",
                 {{"start", instant},
                  {"end", instant},
                  {"step",
                   {{"type", "string"},
                    {"description", "a positive duration: 15m, 1h30m, 90s, 2d or PT15M"}}}}}};
  Json s = Json::object();
  s["description"] = std::string(description);
  s["anyOf"] = Json::array({instant, interval, range});
  s["default"] = value.end ? Json({{"start", value.start.format()},
                                   {"end", value.end->format()},
                                   {"step", formatDuration(value.stepSeconds)}})
                           : Json(value.start.format());
  mSchema["properties"][std::string(key)] = std::move(s);
}

void SchemaBuilder::field(std::string_view key, const std::optional<IsoTime>& value,
                          std::string_view description) {
  // An instant, or empty text for none (the reader takes "" as no key).
  Json s = Json::object();
  s["description"] = std::string(description);
  s["type"] = "string";
  s["anyOf"] = Json::array({Json{{"maxLength", 0}}, Json{{"pattern", kIsoTimePattern}}});
  if (value) s["default"] = value->format();
  mSchema["properties"][std::string(key)] = std::move(s);
}

void SchemaBuilder::bothOrNeither(std::string_view a, std::string_view b) {
  mSchema["dependentRequired"][std::string(a)] = Json::array({std::string(b)});
  mSchema["dependentRequired"][std::string(b)] = Json::array({std::string(a)});
}

}  // namespace sky::detail
