// ConfigNode basics and the YAML front end (yaml-cpp 0.7). The JSON front end lives in
// config_tree_json.cpp.
#include "engine/scene/config_tree.h"

#include <functional>
#include <map>
#include <sstream>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include "engine/core/error.h"

namespace sky {

std::string SourcePos::str() const {
  if (line <= 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

ConfigNode ConfigNode::makeNull(SourcePos pos) {
  ConfigNode n;
  n.kind = Kind::Null;
  n.pos = std::move(pos);
  return n;
}

ConfigNode ConfigNode::makeScalar(std::string text, Style style, SourcePos pos) {
  ConfigNode n;
  n.kind = Kind::Scalar;
  n.style = style;
  n.text = std::move(text);
  n.pos = std::move(pos);
  return n;
}

ConfigNode ConfigNode::makeSequence(SourcePos pos) {
  ConfigNode n;
  n.kind = Kind::Sequence;
  n.pos = std::move(pos);
  return n;
}

ConfigNode ConfigNode::makeMap(SourcePos pos) {
  ConfigNode n;
  n.kind = Kind::Map;
  n.pos = std::move(pos);
  return n;
}

const ConfigNode* ConfigNode::find(std::string_view name) const {
  if (kind != Kind::Map) return nullptr;
  for (const ConfigNode& c : children)
    if (c.key == name) return &c;
  return nullptr;
}

ConfigNode* ConfigNode::find(std::string_view name) {
  return const_cast<ConfigNode*>(static_cast<const ConfigNode*>(this)->find(name));
}

ConfigNode& ConfigNode::add(std::string name, SourcePos namePos, ConfigNode value) {
  value.key = std::move(name);
  value.keyPos = std::move(namePos);
  children.push_back(std::move(value));
  return children.back();
}

std::string ConfigNode::describeKind() const {
  switch (kind) {
    case Kind::Null:
      return "null";
    case Kind::Sequence:
      return "a list";
    case Kind::Map:
      return "a map";
    case Kind::Scalar:
      break;
  }
  switch (style) {
    case Style::String:
      return "a string";
    case Style::Number:
      return "a number";
    case Style::Bool:
      return "a boolean";
    case Style::Plain:
      break;
  }
  return "'" + messageText(text) + "'";
}

size_t illFormedUtf8At(std::string_view text) {
  const auto byte = [&](size_t i) { return static_cast<unsigned char>(text[i]); };
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = byte(i);
    if (c < 0x80) {
      ++i;
      continue;
    }
    // The sequence's length and the range its second byte must lie in (which rules out
    // overlong forms, surrogates and code points past U+10FFFF).
    size_t n = 0;
    unsigned char lo = 0x80, hi = 0xBF;
    if (c >= 0xC2 && c <= 0xDF) n = 2;
    else if (c == 0xE0) n = 3, lo = 0xA0;
    else if (c == 0xED) n = 3, hi = 0x9F;
    else if (c >= 0xE1 && c <= 0xEF) n = 3;
    else if (c == 0xF0) n = 4, lo = 0x90;
    else if (c == 0xF4) n = 4, hi = 0x8F;
    else if (c >= 0xF1 && c <= 0xF3) n = 4;
    if (n == 0 || i + n > text.size() || byte(i + 1) < lo || byte(i + 1) > hi) return i;
    for (size_t k = 2; k < n; ++k)
      if ((byte(i + k) & 0xC0) != 0x80) return i;
    i += n;
  }
  return std::string_view::npos;
}

std::string messageText(std::string_view text, size_t maxLength) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    // Cut at a UTF-8 character boundary.
    if (out.size() >= maxLength && (static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      out += "...";
      break;
    }
    unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (c == '\r')
      out += "\\r";
    else if (c < 0x20 || c == 0x7F) {
      static const char* kHex = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

namespace {

constexpr const char* kStrTag = "tag:yaml.org,2002:str";

// Builds the tree from yaml-cpp parser events rather than YAML::Node: events carry a mark
// for every node and keep duplicate keys visible, and the parser loop stays in our hands
// (yaml-cpp 0.7's YAML::Load silently drops a document that starts with a stray ',',
// and YAML::LoadAll loops forever on it).
// yaml-cpp reports events before it has seen the whole document, so the first error of
// ours is kept and raised only if the document turns out to be valid YAML: a syntax error
// explains more than whatever the half-parsed events looked like.
class YamlTreeBuilder : public YAML::EventHandler {
public:
  using At = std::function<SourcePos(const YAML::Mark&)>;

  explicit YamlTreeBuilder(At at) : mAt(std::move(at)) {}

  bool hasRoot() const { return mHasRoot; }
  const std::string& error() const { return mError; }
  ConfigNode takeRoot() { return std::move(mRoot); }
  const YAML::Mark& documentStart() const { return mDocumentStart; }

  void OnDocumentStart(const YAML::Mark& mark) override { mDocumentStart = mark; }
  void OnDocumentEnd() override {}

  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    if (failed()) return;
    place(ConfigNode::makeNull(mAt(mark)), anchor);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    if (failed()) return;
    auto it = mAnchors.find(anchor);
    if (it == mAnchors.end())
      return fail(mAt(mark), path(), "alias to an anchor that is not complete yet");
    // Each alias is a copy of its anchor's tree. Nine levels of `&a [*b, *b, ...]` in 1 KB of
    // text expand to billions of nodes (issue 31, 6): the copies are counted, and past a
    // bound no scene needs the file is refused where the alias stands.
    mAliasNodes += nodeCount(it->second);
    if (mAliasNodes > kMaxAliasNodes)
      return fail(mAt(mark), path(),
                  "YAML aliases expand to more than " + std::to_string(kMaxAliasNodes) +
                      " nodes (an alias bomb?)");
    ConfigNode copy = it->second;
    copy.pos = mAt(mark);
    place(std::move(copy), 0);
  }
  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                const std::string& value) override {
    if (failed()) return;
    ConfigNode::Style style = ConfigNode::Style::Plain;
    if (tag == "!" || tag == kStrTag)
      style = ConfigNode::Style::String;
    else if (tag != "?")
      return fail(mAt(mark), path(), "unsupported YAML tag '" + tag + "'");
    place(ConfigNode::makeScalar(value, style, mAt(mark)), anchor);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    if (failed() || !checkCollectionTag(mark, tag, "tag:yaml.org,2002:seq")) return;
    open(ConfigNode::makeSequence(mAt(mark)), anchor);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    if (failed() || !checkCollectionTag(mark, tag, "tag:yaml.org,2002:map")) return;
    open(ConfigNode::makeMap(mAt(mark)), anchor);
  }
  void OnMapEnd() override { close(); }

private:
  // An open container. Maps alternate key and value events; the key waits here.
  struct Frame {
    ConfigNode* node;
    YAML::anchor_t anchor;
    bool haveKey = false;
    std::string key;
    SourcePos keyPos;
  };

  // Nodes that aliases may add to a document, all together: a scene's tree is a few hundred
  // nodes, and the text itself is capped (kMaxSceneFileBytes).
  static constexpr size_t kMaxAliasNodes = 100000;
  // The nodes of a tree, counted up to just past kMaxAliasNodes (a bomb's anchors are
  // themselves huge).
  static size_t nodeCount(const ConfigNode& node) {
    size_t n = 1;
    for (const ConfigNode& c : node.children) {
      n += nodeCount(c);
      if (n > kMaxAliasNodes) break;
    }
    return n;
  }

  bool failed() const { return !mError.empty(); }
  // Records the error; every later event is ignored.
  void fail(const SourcePos& pos, const std::string& path, const std::string& what) {
    mError = pos.str() + ": " + (path.empty() ? "" : messageText(path) + ": ") + what;
  }

  bool checkCollectionTag(const YAML::Mark& mark, const std::string& tag, const char* core) {
    if (tag == "?" || tag == "!" || tag == core) return true;
    fail(mAt(mark), path(), "unsupported YAML tag '" + tag + "'");
    return false;
  }

  // Puts a finished node where it belongs; returns it, or nullptr when it was a map key
  // (or was refused).
  ConfigNode* place(ConfigNode node, YAML::anchor_t anchor) {
    if (anchor) mAnchors[anchor] = node;  // scalars; containers are recorded when they close
    if (mStack.empty()) {
      mRoot = std::move(node);
      mHasRoot = true;
      return &mRoot;
    }
    Frame& top = mStack.back();
    if (top.node->kind == ConfigNode::Kind::Sequence) {
      top.node->children.push_back(std::move(node));
      return &top.node->children.back();
    }
    if (!top.haveKey) {
      if (node.kind != ConfigNode::Kind::Scalar) {
        fail(node.pos, path(), "map keys must be plain names");
        return nullptr;
      }
      if (const ConfigNode* prev = top.node->find(node.text)) {
        fail(node.pos, childPath(node.text),
             "duplicate key (first given at line " + std::to_string(prev->keyPos.line) + ")");
        return nullptr;
      }
      top.haveKey = true;
      top.key = node.text;
      top.keyPos = node.pos;
      return nullptr;
    }
    // yaml-cpp marks an empty value (`key:`) at the start of the next line; the key's
    // position is the one a user can find.
    if (node.kind == ConfigNode::Kind::Null) node.pos = top.keyPos;
    top.haveKey = false;
    return &top.node->add(std::move(top.key), top.keyPos, std::move(node));
  }

  // Containers stay on the stack while open. Pointers into parents' child vectors are
  // safe: a parent gains no children while one of its children is open.
  void open(ConfigNode node, YAML::anchor_t anchor) {
    // nullptr only when refused: place() does not take containers as keys.
    if (ConfigNode* placed = place(std::move(node), 0)) mStack.push_back(Frame{placed, anchor});
  }
  void close() {
    if (failed()) return;
    Frame frame = mStack.back();
    mStack.pop_back();
    if (frame.anchor) mAnchors[frame.anchor] = *frame.node;
  }

  // Key path of the node being parsed: "camera.pitch", "lighting.palette[0].sky_color[1]".
  std::string path() const {
    std::string p;
    for (size_t i = 1; i < mStack.size(); ++i) {
      const ConfigNode& parent = *mStack[i - 1].node;
      if (parent.isMap())
        p += (p.empty() ? "" : ".") + mStack[i].node->key;
      else
        p += "[" + std::to_string(parent.children.size() - 1) + "]";
    }
    if (!mStack.empty() && mStack.back().haveKey) p += (p.empty() ? "" : ".") + mStack.back().key;
    return p;
  }
  std::string childPath(const std::string& key) const {
    std::string p = path();
    return p.empty() ? key : p + "." + key;
  }

  At mAt;
  std::vector<Frame> mStack;
  std::map<YAML::anchor_t, ConfigNode> mAnchors;
  size_t mAliasNodes = 0;  // nodes added by aliases so far
  ConfigNode mRoot;
  bool mHasRoot = false;
  YAML::Mark mDocumentStart;
  std::string mError;
};

// Parses the first document and refuses a second one. `at` turns a yaml-cpp mark into our
// position, so files (real marks) and --set values (one fixed position) share the code.
ConfigNode parseOneDocument(std::string_view text, const YamlTreeBuilder::At& at) {
  std::istringstream in{std::string(text)};
  try {
    YAML::Parser parser(in);
    YamlTreeBuilder first(at);
    if (!parser.HandleNextDocument(first)) return ConfigNode::makeNull(at(YAML::Mark()));
    YamlTreeBuilder second(at);
    if (parser.HandleNextDocument(second)) {
      const YAML::Mark& m = second.documentStart();
      // The same start twice means the parser made no progress: a token it cannot place.
      if (m.pos == first.documentStart().pos)
        inputError(at(m).str() + ": YAML syntax error: unexpected text");
      inputError(at(m).str() + ": more than one YAML document (one scene per file)");
    }
    if (!first.error().empty()) inputError(first.error());
    if (!first.hasRoot()) return ConfigNode::makeNull(at(YAML::Mark()));
    return first.takeRoot();
  } catch (const YAML::Exception& e) {
    // yaml-cpp quotes the offending character raw ("unknown escape character: " and a NUL,
    // a CR): escaped, so the error stays one line (found by tests/fuzz/scene_fuzz).
    inputError(at(e.mark).str() + ": YAML syntax error: " + messageText(e.msg, 200));
  }
}

}  // namespace

ConfigNode parseYamlTree(std::string_view text, const std::string& sourceName) {
  auto at = [&](const YAML::Mark& m) {
    if (m.is_null()) return SourcePos{sourceName, 1, 1};
    return SourcePos{sourceName, m.line + 1, m.column + 1};
  };
  ConfigNode root = parseOneDocument(text, at);
  // An empty document (or only comments) is an empty scene.
  if (root.kind == ConfigNode::Kind::Null) return ConfigNode::makeMap(SourcePos{sourceName, 1, 1});
  if (!root.isMap())
    inputError(root.pos.str() + ": expected a map of sections at the top level, got " +
               root.describeKind());
  return root;
}

ConfigNode parseYamlValue(std::string_view text, const SourcePos& pos) {
  return parseOneDocument(text, [&](const YAML::Mark&) { return pos; });
}

}  // namespace sky
