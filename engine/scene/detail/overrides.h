#pragma once
// Command-line overrides: `--set key.path=value` edits the parsed document tree before the
// typed read, so an override goes through exactly the validation a file value does.
#include <string>

#include "engine/scene/config_tree.h"

namespace sky::detail {

// Applies one "key.path=value" to `root` (a Map). The value is a YAML scalar or flow list.
// Errors (malformed text, a path through a non-section or into a list's items) throw
// sky::Error(BadInput) and start with "--set <text>"; the nodes it adds carry that same position
// for later errors.
void applyOverride(ConfigNode& root, const std::string& text);

}  // namespace sky::detail
