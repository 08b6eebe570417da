#include "engine/scene/detail/scene_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

void SceneReader::field(std::string_view key, glm::dvec2& value, NumberRange range,
                        std::string_view) {
  const ConfigNode* node = mMap.find(key);
  if (!node) return;
  std::string path = childPath(key);
  if (node->kind != ConfigNode::Kind::Sequence || node->children.size() != 2) {
    fail(*node, path,
         "expected a list of 2 numbers [from, to], got " +
             (node->kind == ConfigNode::Kind::Sequence
                  ? "a list of " + std::to_string(node->children.size())
                  : node->describeKind()));
  }
  for (int i = 0; i < 2; ++i)
    value[i] = number(node->children[static_cast<size_t>(i)], path + "[" + std::to_string(i) + "]",
                      range, "a number");
}

void SceneReader::field(std::string_view key, bool& value, std::string_view) {
  const ConfigNode* node = mMap.find(key);
  if (!node) return;
  // JSON true/false, or the plain YAML words true/false (not yes/no/on/off: YAML 1.2).
  const bool typed =
      node->kind == ConfigNode::Kind::Scalar &&
      (node->style == ConfigNode::Style::Bool || node->style == ConfigNode::Style::Plain) &&
      (node->text == "true" || node->text == "false");
  if (!typed) {
    fail(*node, childPath(key),
         "expected true or false, got " + (node->kind == ConfigNode::Kind::Scalar
                                               ? "'" + messageText(node->text) + "'"
                                               : node->describeKind()));
  }
  value = node->text == "true";
}

std::string SceneReader::text(const ConfigNode& node, const std::string& path,
                              const TextRule& rule) {
  if (!isTextLike(node)) fail(node, path, "expected a string, got " + node.describeKind());
  const std::string& text = node.text;
  if (text.size() < rule.minLength) {
    fail(node, path,
         rule.minLength == 1
             ? std::string("must not be empty")
             : "must have at least " + std::to_string(rule.minLength) + " characters");
  }
  if (rule.maxLength && text.size() > rule.maxLength)
    fail(node, path, "is longer than " + std::to_string(rule.maxLength) + " characters");
  if (const size_t bad = illFormedUtf8At(text); bad != std::string::npos) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(text[bad]));
    fail(node, path,
         std::string("is not valid UTF-8 (byte ") + hex + " at " + std::to_string(bad) +
             "); write the text in UTF-8");
  }
  if (rule.pattern && !std::regex_search(text, std::regex(rule.pattern, std::regex::ECMAScript)))
    fail(node, path,
         "'" + messageText(text) + "' is not allowed: use " +
             (rule.wording ? rule.wording : rule.pattern));
  return text;
}

void SceneReader::field(std::string_view key, std::string& value, const TextRule& rule,
                        std::string_view) {
  if (const ConfigNode* node = mMap.find(key)) value = text(*node, childPath(key), rule);
}

void SceneReader::field(std::string_view key, std::vector<std::string>& values,
                        const TextRule& rule, std::string_view) {
  const ConfigNode* node = mMap.find(key);
  if (!node) return;
  const std::string path = childPath(key);
  const std::vector<const ConfigNode*> items = sequenceItems(*node, path, "strings");
  values.clear();
  for (size_t i = 0; i < items.size(); ++i)
    values.push_back(text(*items[i], path + "[" + std::to_string(i) + "]", rule));
}

std::vector<const ConfigNode*> SceneReader::sequenceItems(const ConfigNode& node,
                                                          const std::string& path,
                                                          const std::string& what) {
  if (node.kind != ConfigNode::Kind::Sequence)
    fail(node, path, "expected a list of " + what + ", got " + node.describeKind());
  if (node.children.empty())
    fail(node, path, "an empty list; give at least one, or leave the key out");
  std::vector<const ConfigNode*> items;
  for (const ConfigNode& child : node.children) items.push_back(&child);
  return items;
}

void SceneReader::field(std::string_view key, std::optional<glm::dvec2>& value, NumberRange range,
                        std::string_view description) {
  if (!mMap.find(key)) return;
  glm::dvec2 v(0.0);
  field(key, v, range, description);
  value = v;
}

size_t SceneReader::choice(const ConfigNode& node, const std::string& path,
                           const std::vector<std::string_view>& names) {
  if (!isTextLike(node)) fail(node, path, "expected a string, got " + node.describeKind());
  if (node.text.empty()) fail(node, path, "must not be empty");
  for (size_t i = 0; i < names.size(); ++i)
    if (node.text == names[i]) return i;
  std::string wording;  // "a, b or c"
  for (size_t i = 0; i < names.size(); ++i)
    wording += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + std::string(names[i]);
  fail(node, path, "'" + messageText(node.text) + "' is not allowed: use " + wording);
}

namespace {

// One end of a time range or a single instant; `where` names the part in messages.
IsoTime readInstant(const ConfigNode& node, const std::string& path, std::string_view text,
                    const char* where) {
  std::string why;
  std::optional<IsoTime> t = IsoTime::parse(text, &why);
  if (!t)
    inputError(node.pos.str() + ": " + path + ": " + where + "'" + messageText(text) +
               "' is not a valid time: " + why);
  return *t;
}

}  // namespace

void SceneReader::field(std::string_view key, std::optional<IsoTime>& value, std::string_view) {
  const ConfigNode* node = mMap.find(key);
  if (!node) return;
  const std::string path = childPath(key);
  if (!isTextLike(*node)) fail(*node, path, "expected a string, got " + node->describeKind());
  // Empty text means the same as no key (older scenes write `time: ""`).
  value = node->text.empty() ? std::nullopt
                             : std::optional<IsoTime>(readInstant(*node, path, node->text, ""));
}

void SceneReader::field(std::string_view key, TimeSettings& value, std::string_view) {
  const ConfigNode* node = mMap.find(key);
  if (!node) return;
  const std::string path = childPath(key);
  TimeSettings result;
  // Positions and paths of the three parts: the map form has a node per part, the
  // "START/END/STEP" text shares one.
  const ConfigNode* endNode = node;
  const ConfigNode* stepNode = node;
  std::string endPath = path, stepPath = path;
  std::string endText, stepText;
  const char* endWhere = "";
  const char* stepWhere = "";
  if (isTextLike(*node)) {
    std::vector<std::string_view> parts;
    std::string_view text = node->text;
    for (size_t start = 0;;) {
      size_t slash = text.find('/', start);
      parts.push_back(text.substr(start, slash == std::string_view::npos ? slash : slash - start));
      if (slash == std::string_view::npos) break;
      start = slash + 1;
    }
    if (parts.size() != 1 && parts.size() != 3)
      fail(*node, path,
           "'" + messageText(node->text) +
               "' is neither a time nor a range START/END/STEP (e.g. "
               "2024-06-21T00:00Z/2024-06-22T00:00Z/15m)");
    result.start = readInstant(*node, path, parts[0], parts.size() == 1 ? "" : "start ");
    if (parts.size() == 1) {
      value = result;
      return;
    }
    endText = parts[1];
    stepText = parts[2];
    endWhere = "end ";
    stepWhere = "step ";
  } else if (node->isMap()) {
    static const std::vector<std::string> kKeys = {"start", "end", "step"};
    checkKeys(*node, path, kKeys);
    requireAll(*node, path, kKeys);
    const ConfigNode* startNode = node->find("start");
    endNode = node->find("end");
    stepNode = node->find("step");
    for (const ConfigNode* part : {startNode, endNode, stepNode}) {
      if (!isTextLike(*part))
        fail(*part, path + "." + part->key, "expected a string, got " + part->describeKind());
    }
    result.start = readInstant(*startNode, path + ".start", startNode->text, "");
    endText = endNode->text;
    stepText = stepNode->text;
    endPath = path + ".end";
    stepPath = path + ".step";
  } else {
    fail(*node, path,
         "expected an ISO 8601 time, START/END/STEP or a {start, end, step} map, got " +
             node->describeKind());
  }
  result.end = readInstant(*endNode, endPath, endText, endWhere);
  std::string why;
  std::optional<double> step = parseDuration(stepText, &why);
  if (!step)
    fail(*stepNode, stepPath,
         std::string(stepWhere) + "'" + messageText(stepText) + "' is not a duration: " + why);
  if (!(*step > 0))
    fail(*stepNode, stepPath,
         std::string(stepWhere) + "'" + messageText(stepText) + "' must be positive");
  result.stepSeconds = *step;
  if (result.end->secondsSince(result.start) < 0)
    fail(*endNode, endPath,
         std::string(endWhere) + "'" + messageText(endText) + "' is before the start " +
             result.start.format());
  // Compared in double first: a tiny step over a long range overflows the frame count.
  // Then frameCount() itself, which counts a range a hair short of a whole number of steps
  // as whole (99999.9999999999 steps is 100001 frames).
  if (result.end->secondsSince(result.start) / result.stepSeconds >=
          static_cast<double>(TimeSettings::kMaxFrames) ||
      result.frameCount() > TimeSettings::kMaxFrames)
    fail(*stepNode, stepPath,
         "the range has more than " + std::to_string(TimeSettings::kMaxFrames) +
             " frames; use a longer step or a shorter range");
  value = result;
}

void SceneReader::checkList(const ConfigNode& list, const std::string& path, const ListRule& rule) {
  if (list.kind != ConfigNode::Kind::Sequence)
    fail(list, path, "expected a list of maps, got " + list.describeKind());
  size_t n = list.children.size();
  if (n < rule.minItems || (rule.maxItems && n > rule.maxItems))
    fail(list, path,
         "expected " + std::to_string(rule.minItems) + " to " + std::to_string(rule.maxItems) +
             " items, got " + std::to_string(n));
  for (size_t i = 0; i < n; ++i) {
    if (!list.children[i].isMap())
      fail(list.children[i], path + "[" + std::to_string(i) + "]",
           "expected a map of settings, got " + list.children[i].describeKind());
  }
}

void SceneReader::requireAll(const ConfigNode& map, const std::string& path,
                             const std::vector<std::string>& known) {
  for (const std::string& key : known) {
    if (!map.find(key)) fail(map, path, "missing key '" + key + "'");
  }
}

void SceneReader::checkIncreasing(const ConfigNode& list, const std::string& path,
                                  const ListRule& rule) {
  if (!rule.increasingKey) return;
  // Items are already read and validated, so every value parses.
  std::optional<double> previous;
  for (size_t i = 0; i < list.children.size(); ++i) {
    const ConfigNode* n = list.children[i].find(rule.increasingKey);
    double v = *parseNumber(n->text);
    if (previous && !(v > *previous))
      fail(*n, path + "[" + std::to_string(i) + "]." + rule.increasingKey,
           messageText(n->text) + " must be greater than the previous item's " +
               formatDouble(*previous) + " (list items in increasing " + rule.increasingKey + ")");
    previous = v;
  }
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

void SceneReader::check(std::string_view key, bool ok, std::string_view what) {
  if (ok) return;
  const ConfigNode* node = mMap.find(key);
  fail(node ? *node : mMap, childPath(key), std::string(what));
}

}  // namespace sky::detail
