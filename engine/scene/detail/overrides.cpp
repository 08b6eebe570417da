#include "engine/scene/detail/overrides.h"

#include <algorithm>
#include <vector>

#include "engine/core/error.h"

namespace sky::detail {
namespace {

// "palette.0" or "palette[0]": a list item. Scene keys are snake_case names, never numbers.
bool isItemKey(const std::string& key) {
  return key.find_first_of("[]") != std::string::npos ||
         std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Items of a list (the lighting palette) cannot be edited one key at a time: the override
// works on the document tree, where an item would have to be invented as a map the reader
// then rejects with a message about the list, not about the override.
[[noreturn]] void listItemError(const SourcePos& pos, const std::string& path,
                                const std::string& list) {
  inputError(pos.str() + ": cannot set '" + messageText(path) + "': '" + messageText(list) +
             "' is a list and --set cannot address its items; set the whole list (" +
             messageText(list) + "=[...]) or edit the scene file");
}

}  // namespace

void applyOverride(ConfigNode& root, const std::string& text) {
  // No line: errors read "--set output.widht=3: unknown key ...".
  SourcePos pos{"--set " + messageText(text, 120), 0, 0};
  size_t eq = text.find('=');
  if (eq == std::string::npos)
    inputError(pos.str() + ": malformed override: expected key.path=value");
  std::string path = text.substr(0, eq);
  if (path.empty())
    inputError(pos.str() + ": malformed override: the key path before '=' is empty");

  std::vector<std::string> keys;
  for (size_t start = 0;;) {
    size_t dot = path.find('.', start);
    std::string key =
        path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (key.empty())
      inputError(pos.str() + ": malformed override: empty key in '" + messageText(path) + "'");
    if (isItemKey(key)) {
      // The list is what comes before the index: "a.b" in "a.b.0.c" and in "a.b[0].c".
      size_t bracket = key.find('[');
      std::string list = path.substr(0, start) +
                         (bracket == std::string::npos ? std::string() : key.substr(0, bracket));
      if (!list.empty() && list.back() == '.') list.pop_back();
      // A leading index ("0.x") names no list; the reader reports the unknown key.
      if (!list.empty()) listItemError(pos, path, list);
    }
    keys.push_back(std::move(key));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }

  ConfigNode value = parseYamlValue(std::string_view(text).substr(eq + 1), pos);
  if (value.isMap())
    inputError(
        pos.str() +
        ": an override value must be a scalar or a [list], not a map; set one key at a time");

  // Sections missing from the file are created (the reader then checks their names);
  // anything else in the way is an error, since replacing a value by a section would
  // silently throw the file's value away.
  ConfigNode* map = &root;
  std::string walked;
  for (size_t i = 0; i + 1 < keys.size(); ++i) {
    walked += (i ? "." : "") + keys[i];
    ConfigNode* next = map->find(keys[i]);
    if (!next)
      next = &map->add(keys[i], pos, ConfigNode::makeMap(pos));
    else if (next->kind == ConfigNode::Kind::Sequence)
      listItemError(pos, path, walked);
    else if (!next->isMap())
      inputError(pos.str() + ": cannot set '" + messageText(path) + "': '" + messageText(walked) +
                 "' is not a section (it holds " + next->describeKind() + ")");
    map = next;
  }
  if (ConfigNode* existing = map->find(keys.back())) {
    std::string key = existing->key;
    *existing = std::move(value);
    existing->key = std::move(key);
    existing->keyPos = pos;
  } else {
    map->add(keys.back(), pos, std::move(value));
  }
}

}  // namespace sky::detail
