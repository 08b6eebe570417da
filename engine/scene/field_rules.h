#pragma once
// Value rules attached to scene fields in scene_fields.h. Each rule is checked by the
// reader and written into the JSON Schema by the same description, so they cannot drift.
#include <cstddef>
#include <optional>
#include <string_view>
#include <type_traits>

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

// One value of a scene choice and its name in the file. Each choice is an enum class with
// one table of these, enumNames(E{}) next to the enum (scene.h), in the order messages and the
// JSON Schema list them: the reader accepts exactly these names (any other is "'x' is not
// allowed: use a, b or c"), the writer prints them, and the code past the scene layer switches
// on the enum.
template <class E>
struct EnumName {
  E value;
  const char* name;
};

template <class E>
concept SceneEnum = std::is_enum_v<E> && requires {
  enumNames(E{});
};

// The file name of `value`.
template <SceneEnum E>
constexpr const char* enumName(E value) {
  for (const EnumName<E>& n : enumNames(E{}))
    if (n.value == value) return n.name;
  return "";
}

// The value whose file name is `name`, if any.
template <SceneEnum E>
constexpr std::optional<E> enumValue(std::string_view name) {
  for (const EnumName<E>& n : enumNames(E{}))
    if (name == n.name) return n.value;
  return std::nullopt;
}

}  // namespace sky
