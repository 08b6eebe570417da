#pragma once
// Value rules attached to scene fields in scene_fields.h. Each rule is checked by the
// reader and written into the JSON Schema by the same description, so they cannot drift.
#include <cstddef>

namespace sky {

// Inclusive range for a number (each component for colours). Non-finite values never pass.
struct NumberRange {
  double min;
  double max;
};

// Rules for a string: length in bytes and an optional ECMAScript pattern (anchored with
// ^...$ as JSON Schema patterns are not), with a short human wording for error messages.
struct TextRule {
  size_t minLength = 0;
  size_t maxLength = 0;           // 0: no limit
  const char* pattern = nullptr;  // ECMAScript, used by std::regex and by the schema
  const char* wording = nullptr;  // "letters, digits, '.', '_' and '-', not starting with '.'"
};

// Rules for a list of sections (palette keyframes): its length, and a number key whose
// values must strictly increase down the list (nullptr: any order). Every item gives every key.
struct ListRule {
  size_t minItems = 0;
  size_t maxItems = 0;                  // 0: no limit
  const char* increasingKey = nullptr;  // e.g. "sun_elevation"
};

}  // namespace sky
