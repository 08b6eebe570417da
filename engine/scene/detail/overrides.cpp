#include "engine/scene/detail/overrides.h"

#include <vector>

#include "engine/core/error.h"

namespace sky::detail {

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
