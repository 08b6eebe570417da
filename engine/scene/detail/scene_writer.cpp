#include "engine/scene/detail/scene_writer.h"

#include <algorithm>
#include <charconv>

#include "engine/core/error.h"
#include "engine/scene/detail/number_text.h"

namespace sky::detail {
namespace {

ConfigNode number(std::string text) {
  return ConfigNode::makeScalar(std::move(text), ConfigNode::Style::Number, {});
}

// JSON string escaping is also valid YAML double-quoted escaping.
std::string quoted(const std::string& s) {
  return nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string scalarText(const ConfigNode& n) {
  if (n.kind == ConfigNode::Kind::Null) return "null";
  if (n.style == ConfigNode::Style::String) return quoted(n.text);
  return n.text;
}

// Lists and maps inside a list are printed in flow style by both emitters.
std::string flowText(const ConfigNode& n, bool json) {
  switch (n.kind) {
    case ConfigNode::Kind::Sequence: {
      std::string s = "[";
      for (size_t i = 0; i < n.children.size(); ++i)
        s += (i ? ", " : "") + flowText(n.children[i], json);
      return s + "]";
    }
    case ConfigNode::Kind::Map: {
      std::string s = "{";
      for (size_t i = 0; i < n.children.size(); ++i) {
        const ConfigNode& c = n.children[i];
        s += (i ? ", " : "") + (json ? quoted(c.key) : c.key) + ": " + flowText(c, json);
      }
      return s + "}";
    }
    default:
      return scalarText(n);
  }
}

bool isListOfMaps(const ConfigNode& n) {
  return n.kind == ConfigNode::Kind::Sequence && !n.children.empty() &&
         std::all_of(n.children.begin(), n.children.end(),
                     [](const ConfigNode& c) { return c.isMap() && !c.children.empty(); });
}

void yamlMap(const ConfigNode& map, int indent, std::string& out, bool firstInItem = false);

// "- key: value" then the item's other keys aligned under the first.
void yamlListOfMaps(const ConfigNode& list, int indent, std::string& out) {
  for (const ConfigNode& item : list.children) {
    out.append(static_cast<size_t>(indent), ' ');
    out += "- ";
    yamlMap(item, indent + 2, out, true);
  }
}

void yamlMap(const ConfigNode& map, int indent, std::string& out, bool firstInItem) {
  for (const ConfigNode& c : map.children) {
    if (!firstInItem) out.append(static_cast<size_t>(indent), ' ');
    firstInItem = false;
    out += c.key + ":";
    if (c.isMap() && !c.children.empty()) {
      out += "\n";
      yamlMap(c, indent + 2, out);
    } else if (isListOfMaps(c)) {
      out += "\n";
      yamlListOfMaps(c, indent + 2, out);
    } else {
      out += " " + flowText(c, false) + "\n";
    }
  }
}

void jsonMap(const ConfigNode& map, int indent, std::string& out) {
  if (map.children.empty()) {
    out += "{}";
    return;
  }
  out += "{\n";
  for (size_t i = 0; i < map.children.size(); ++i) {
    const ConfigNode& c = map.children[i];
    out.append(static_cast<size_t>(indent + 2), ' ');
    out += quoted(c.key) + ": ";
    if (c.isMap()) {
      jsonMap(c, indent + 2, out);
    } else if (isListOfMaps(c)) {
      out += "[\n";
      for (size_t k = 0; k < c.children.size(); ++k) {
        out.append(static_cast<size_t>(indent + 4), ' ');
        jsonMap(c.children[k], indent + 4, out);
        out += k + 1 < c.children.size() ? ",\n" : "\n";
      }
      out.append(static_cast<size_t>(indent + 2), ' ');
      out += "]";
    } else {
      out += flowText(c, true);
    }
    out += i + 1 < map.children.size() ? ",\n" : "\n";
  }
  out.append(static_cast<size_t>(indent), ' ');
  out += "}";
}

}  // namespace

void SceneWriter::field(std::string_view key, const int& value, NumberRange, std::string_view) {
  mMap.add(std::string(key), {}, number(std::to_string(value)));
}

void SceneWriter::field(std::string_view key, const double& value, NumberRange, std::string_view) {
  mMap.add(std::string(key), {}, number(formatDouble(value)));
}

void SceneWriter::field(std::string_view key, const std::optional<double>& value, NumberRange,
                        std::string_view) {
  // Absent stays absent: an explicit value would change what the scene means.
  if (value) mMap.add(std::string(key), {}, number(formatDouble(*value)));
}

void SceneWriter::field(std::string_view key, const glm::vec3& value, NumberRange,
                        std::string_view) {
  ConfigNode list = ConfigNode::makeSequence({});
  for (int i = 0; i < 3; ++i) list.children.push_back(number(formatFloat(value[i])));
  mMap.add(std::string(key), {}, std::move(list));
}

void SceneWriter::field(std::string_view key, const glm::dvec2& value, NumberRange,
                        std::string_view) {
  ConfigNode list = ConfigNode::makeSequence({});
  for (int i = 0; i < 2; ++i) list.children.push_back(number(formatDouble(value[i])));
  mMap.add(std::string(key), {}, std::move(list));
}

void SceneWriter::field(std::string_view key, const bool& value, std::string_view) {
  mMap.add(std::string(key), {},
           ConfigNode::makeScalar(value ? "true" : "false", ConfigNode::Style::Bool, {}));
}

void SceneWriter::field(std::string_view key, const std::string& value, const TextRule&,
                        std::string_view) {
  mMap.add(std::string(key), {}, ConfigNode::makeScalar(value, ConfigNode::Style::String, {}));
}

void SceneWriter::field(std::string_view key, const std::vector<std::string>& values,
                        const TextRule&, std::string_view) {
  if (values.empty()) return;  // absent: the key's default, no list
  ConfigNode list = ConfigNode::makeSequence({});
  for (const std::string& v : values)
    list.children.push_back(ConfigNode::makeScalar(v, ConfigNode::Style::String, {}));
  mMap.add(std::string(key), {}, std::move(list));
}

void SceneWriter::choice(std::string_view key, const char* name) {
  mMap.add(std::string(key), {}, ConfigNode::makeScalar(name, ConfigNode::Style::String, {}));
}

void SceneWriter::field(std::string_view key, const std::optional<IsoTime>& value,
                        std::string_view) {
  // Absent stays absent, as for optional numbers.
  if (value)
    mMap.add(std::string(key), {},
             ConfigNode::makeScalar(value->format(), ConfigNode::Style::String, {}));
}

void SceneWriter::field(std::string_view key, const TimeSettings& value, std::string_view) {
  auto text = [](std::string t) {
    return ConfigNode::makeScalar(std::move(t), ConfigNode::Style::String, {});
  };
  if (!value.end) {
    mMap.add(std::string(key), {}, text(value.start.format()));
    return;
  }
  ConfigNode range = ConfigNode::makeMap({});
  range.add("start", {}, text(value.start.format()));
  range.add("end", {}, text(value.end->format()));
  range.add("step", {}, text(formatDuration(value.stepSeconds)));
  mMap.add(std::string(key), {}, std::move(range));
}

void SceneWriter::checkPairs() const {
  // A scene built in code with only one of the pair would print a file that does not load.
  for (const auto& [a, b] : mPairs) {
    if ((mMap.find(a) == nullptr) != (mMap.find(b) == nullptr))
      internalError("scene writer: '" + a + "' and '" + b + "' must be set together");
  }
}

std::string toYamlText(const ConfigNode& root) {
  std::string out;
  yamlMap(root, 0, out);
  return out;
}

std::string toJsonText(const ConfigNode& root) {
  std::string out;
  jsonMap(root, 0, out);
  return out + "\n";
}

nlohmann::json toJsonValue(const ConfigNode& n) {
  switch (n.kind) {
    case ConfigNode::Kind::Null:
      return nullptr;
    case ConfigNode::Kind::Sequence: {
      nlohmann::json a = nlohmann::json::array();
      for (const ConfigNode& c : n.children) a.push_back(toJsonValue(c));
      return a;
    }
    case ConfigNode::Kind::Map: {
      nlohmann::json o = nlohmann::json::object();
      for (const ConfigNode& c : n.children) o[c.key] = toJsonValue(c);
      return o;
    }
    case ConfigNode::Kind::Scalar:
      break;
  }
  if (n.style == ConfigNode::Style::Bool) return n.text == "true";
  if (n.style == ConfigNode::Style::Number) {
    int64_t i = 0;
    auto [end, ec] = std::from_chars(n.text.data(), n.text.data() + n.text.size(), i);
    if (ec == std::errc() && end == n.text.data() + n.text.size()) return i;
    if (std::optional<double> d = parseNumber(n.text)) return *d;
  }
  return n.text;
}

}  // namespace sky::detail
