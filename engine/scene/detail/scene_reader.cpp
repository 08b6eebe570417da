#include "engine/scene/detail/scene_reader.h"

#include <algorithm>
#include <cmath>
#include <regex>

#include "engine/core/error.h"
#include "engine/scene/detail/key_suggest.h"
#include "engine/scene/detail/number_text.h"

namespace sky::detail {
namespace {

// Whole bounds as plain integers ("1000000", not to_chars' shorter "1e+06").
std::string boundText(double v) {
  if (v == std::floor(v) && std::fabs(v) < 1e15) return std::to_string(static_cast<long long>(v));
  return formatDouble(v);
}

std::string rangeText(NumberRange r) {
  return "[" + boundText(r.min) + ", " + boundText(r.max) + "]";
}

bool isNumberLike(const ConfigNode& n) {
  return n.kind == ConfigNode::Kind::Scalar &&
         (n.style == ConfigNode::Style::Plain || n.style == ConfigNode::Style::Number);
}

bool isTextLike(const ConfigNode& n) {
  // Plain YAML scalars are untyped, so `name: sky` is a string; JSON numbers and booleans
  // are typed and are not.
  return n.kind == ConfigNode::Kind::Scalar &&
         (n.style == ConfigNode::Style::Plain || n.style == ConfigNode::Style::String);
}

}  // namespace

void SceneReader::fail(const ConfigNode& node, const std::string& path, const std::string& what) {
  inputError(node.pos.str() + ": " + path + ": " + what);
}

std::string SceneReader::childPath(std::string_view key) const {
  return mPath.empty() ? std::string(key) : mPath + "." + std::string(key);
}

void SceneReader::checkKeys(const ConfigNode& map, const std::string& path,
                            const std::vector<std::string>& known) {
  for (const ConfigNode& child : map.children) {
    if (std::find(known.begin(), known.end(), child.key) != known.end()) continue;
    std::string full = path.empty() ? child.key : path + "." + child.key;
    std::string hint;
    if (std::string best = suggestKey(child.key, known); !best.empty()) {
      hint = "did you mean '" + best + "'?";
    } else {
      hint = "known keys: ";
      for (size_t i = 0; i < known.size(); ++i) hint += (i ? ", " : "") + known[i];
    }
    inputError(child.keyPos.str() + ": unknown key '" + messageText(full) + "' (" + hint + ")");
  }
}

double SceneReader::number(const ConfigNode& node, const std::string& path, NumberRange range,
                           const char* expected) {
  if (!isNumberLike(node))
    fail(node, path, std::string("expected ") + expected + ", got " + node.describeKind());
  std::optional<double> v = parseNumber(node.text);
  if (!v) fail(node, path, std::string("expected ") + expected + ", got " + node.describeKind());
  // Written as !(in range) so NaN fails too.
  if (!(std::isfinite(*v) && *v >= range.min && *v <= range.max))
    fail(node, path, messageText(node.text) + " is out of range " + rangeText(range));
  return *v;
}

void SceneReader::field(std::string_view key, int& value, NumberRange range, std::string_view) {
  const ConfigNode* node = mMap.find(key);
  if (!node) return;
  std::string path = childPath(key);
  if (!isNumberLike(*node)) fail(*node, path, "expected an integer, got " + node->describeKind());
  // Integral first: "1.5" is not an integer even where 1.5 would be in range. Non-finite
  // text goes on to the range check, which names it.
  if (std::optional<double> v = parseNumber(node->text);
      v && std::isfinite(*v) && *v != std::floor(*v))
    fail(*node, path, "expected an integer, got " + messageText(node->text));
  value = static_cast<int>(number(*node, path, range, "an integer"));
}

void SceneReader::field(std::string_view key, double& value, NumberRange range, std::string_view) {
  if (const ConfigNode* node = mMap.find(key))
    value = number(*node, childPath(key), range, "a number");
}

void SceneReader::field(std::string_view key, std::optional<double>& value, NumberRange range,
                        std::string_view) {
  if (const ConfigNode* node = mMap.find(key))
    value = number(*node, childPath(key), range, "a number");
}

void SceneReader::field(std::string_view key, glm::vec3& value, NumberRange range,
                        std::string_view) {
  const ConfigNode* node = mMap.find(key);
  if (!node) return;
  std::string path = childPath(key);
  if (node->kind != ConfigNode::Kind::Sequence) {
    fail(*node, path, "expected a list of 3 numbers [r, g, b], got " + node->describeKind());
  }
  if (node->children.size() != 3) {
    fail(*node, path,
         "expected a list of 3 numbers [r, g, b], got a list of " +
             std::to_string(node->children.size()));
  }
  glm::vec3 result;
  for (int i = 0; i < 3; ++i) {
    const ConfigNode& item = node->children[static_cast<size_t>(i)];
    number(item, path + "[" + std::to_string(i) + "]", range, "a number");
    // Rounded once from the text, not via double, so printing a float and reading it
    // back gives the same float.
    result[i] = *parseFloat(item.text);
  }
  value = result;
}

void SceneReader::field(std::string_view key, std::string& value, const TextRule& rule,
                        std::string_view) {
  const ConfigNode* node = mMap.find(key);
  if (!node) return;
  std::string path = childPath(key);
  if (!isTextLike(*node)) fail(*node, path, "expected a string, got " + node->describeKind());
  const std::string& text = node->text;
  if (text.size() < rule.minLength) {
    fail(*node, path,
         rule.minLength == 1
             ? std::string("must not be empty")
             : "must have at least " + std::to_string(rule.minLength) + " characters");
  }
  if (rule.maxLength && text.size() > rule.maxLength)
    fail(*node, path, "is longer than " + std::to_string(rule.maxLength) + " characters");
  if (rule.pattern && !std::regex_search(text, std::regex(rule.pattern, std::regex::ECMAScript)))
    fail(*node, path,
         "'" + messageText(text) + "' is not allowed: use " +
             (rule.wording ? rule.wording : rule.pattern));
  value = text;
}

void SceneReader::field(std::string_view key, IsoTime& value, std::string_view) {
  const ConfigNode* node = mMap.find(key);
  if (!node) return;
  std::string path = childPath(key);
  if (!isTextLike(*node))
    fail(*node, path, "expected an ISO 8601 time string, got " + node->describeKind());
  std::string why;
  std::optional<IsoTime> t = IsoTime::parse(node->text, &why);
  if (!t) fail(*node, path, "'" + messageText(node->text) + "' is not a valid time: " + why);
  value = *t;
}

void SceneReader::bothOrNeither(std::string_view a, std::string_view b) {
  const ConfigNode* na = mMap.find(a);
  const ConfigNode* nb = mMap.find(b);
  if (na && !nb)
    inputError(na->keyPos.str() + ": " + childPath(a) + ": given without " + childPath(b) +
               " (give both or neither)");
  if (nb && !na)
    inputError(nb->keyPos.str() + ": " + childPath(b) + ": given without " + childPath(a) +
               " (give both or neither)");
}

}  // namespace sky::detail
