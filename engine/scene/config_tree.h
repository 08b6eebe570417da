#pragma once
// A small document tree shared by the YAML and JSON front ends, so validation, --set
// overrides and error positions are written once. Every node knows where it came from.
#include <string>
#include <string_view>
#include <vector>

namespace sky {

// 1-based position in a source; line 0 means "no line" (a command-line override), and the
// position prints as just the source name.
struct SourcePos {
  std::string file;
  int line = 0;
  int column = 0;

  // "file:line:col", or "file" when there is no line.
  std::string str() const;
};

class ConfigNode {
public:
  enum class Kind { Null, Scalar, Sequence, Map };
  // Plain: an untyped YAML scalar (number, name or word, decided by the reader).
  // String: quoted YAML or a JSON string. Number/Bool: typed JSON values.
  enum class Style { Plain, String, Number, Bool };

  Kind kind = Kind::Null;
  Style style = Style::Plain;        // scalars only
  std::string text;                  // scalars only, as written (JSON numbers as lexed)
  std::vector<ConfigNode> children;  // sequence items or map values, in document order
  std::string key;                   // set on map values: the key they are stored under
  SourcePos keyPos;                  // map values: where the key was written
  SourcePos pos;                     // where the value was written

  static ConfigNode makeNull(SourcePos pos);
  static ConfigNode makeScalar(std::string text, Style style, SourcePos pos);
  static ConfigNode makeSequence(SourcePos pos);
  static ConfigNode makeMap(SourcePos pos);

  bool isMap() const { return kind == Kind::Map; }
  // Map lookup by key; nullptr when absent (or when this is not a map).
  const ConfigNode* find(std::string_view name) const;
  ConfigNode* find(std::string_view name);
  // Appends a map member; the caller has checked that the key is new.
  ConfigNode& add(std::string name, SourcePos namePos, ConfigNode value);

  // "a string", "a number", "a list", ... for type errors.
  std::string describeKind() const;
};

// Text from a document made safe for a one-line error message: control characters escaped
// (a multi-line YAML scalar stays on one line), anything past maxLength bytes cut to "...".
std::string messageText(std::string_view text, size_t maxLength = 60);

// The byte offset of the first sequence in `text` that is not well-formed UTF-8 (RFC 3629:
// no overlong forms, surrogates or code points past U+10FFFF), or npos when there is none.
// JSON files cannot hold such text, and a scene written back would change it (issue 31's
// fuzzing), so the scene reader refuses it in strings.
size_t illFormedUtf8At(std::string_view text);

// Parse a whole document. Syntax errors, duplicate keys and non-name keys throw
// sky::Error(BadInput) as "file:line:col: ...". An empty YAML document is an empty map.
ConfigNode parseYamlTree(std::string_view text, const std::string& sourceName);
ConfigNode parseJsonTree(std::string_view text, const std::string& sourceName);

// Parses a --set value (a YAML scalar or flow sequence); every node gets `pos`.
ConfigNode parseYamlValue(std::string_view text, const SourcePos& pos);

}  // namespace sky
