#pragma once
// Number <-> text for scene files: one parser for YAML plain scalars, JSON numbers and
// --set values, and shortest round-trip printing so `skyrender validate` output reloads
// to bit-identical values.
#include <optional>
#include <string>
#include <string_view>

namespace sky::detail {

// Parses a whole scalar as a decimal number (leading '+' allowed, YAML's .inf/.nan
// spellings map to non-finite values); nullopt if the text is not a number at all.
std::optional<double> parseNumber(std::string_view text);
// Same, rounded once to float (not via double), for glm::vec3 members.
std::optional<float> parseFloat(std::string_view text);

// Shortest text that parses back to exactly `value` (std::to_chars).
std::string formatDouble(double value);
std::string formatFloat(float value);

}  // namespace sky::detail
