#pragma once
// "did you mean" for unknown keys.
#include <string>
#include <string_view>
#include <vector>

namespace sky::detail {

// Optimal-string-alignment distance: insertions, deletions, substitutions and adjacent
// transpositions ("widht" -> "width" is 1).
size_t editDistance(std::string_view a, std::string_view b);

// The closest known key when it is close enough to be a likely typo; empty otherwise.
std::string suggestKey(std::string_view unknown, const std::vector<std::string>& known);

}  // namespace sky::detail
