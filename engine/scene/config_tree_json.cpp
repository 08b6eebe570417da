// JSON front end: nlohmann's SAX parser builds our ConfigNode tree directly. nlohmann keeps
// no positions for values, so the input goes through an iterator that records how many
// bytes the lexer has consumed; each callback turns that into a line and column.
#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/scene/config_tree.h"

namespace sky {
namespace {

// A const char* that reports every step to a shared counter. nlohmann copies iterators
// freely, so the counter lives outside them.
class CountingIterator {
public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  CountingIterator(const char* p, const char* base, size_t* consumed)
      : mPtr(p), mBase(base), mConsumed(consumed) {}
  reference operator*() const { return *mPtr; }
  CountingIterator& operator++() {
    ++mPtr;
    *mConsumed = static_cast<size_t>(mPtr - mBase);
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const CountingIterator& o) const { return mPtr == o.mPtr; }

private:
  const char* mPtr;
  const char* mBase;
  size_t* mConsumed;
};

// Byte offset -> 1-based line and column (columns count UTF-8 code points, like yaml-cpp).
class LineIndex {
public:
  explicit LineIndex(std::string_view text) : mText(text) {
    mStarts.push_back(0);
    for (size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') mStarts.push_back(i + 1);
  }
  SourcePos at(const std::string& file, size_t offset) const {
    if (offset > mText.size()) offset = mText.size();
    size_t line = static_cast<size_t>(std::upper_bound(mStarts.begin(), mStarts.end(), offset) -
                                      mStarts.begin()) -
                  1;
    int column = 1;
    for (size_t i = mStarts[line]; i < offset; ++i)
      if ((static_cast<unsigned char>(mText[i]) & 0xC0) != 0x80) ++column;
    return SourcePos{file, static_cast<int>(line) + 1, column};
  }

private:
  std::string_view mText;
  std::vector<size_t> mStarts;
};

class TreeBuilder {
public:
  using json = nlohmann::json;

  TreeBuilder(std::string_view text, const std::string& file, const size_t& consumed)
      : mText(text), mFile(file), mConsumed(consumed), mLines(text) {}

  ConfigNode takeRoot() { return std::move(mRoot); }

  bool null() { return value(ConfigNode::makeNull(tokenPos())); }
  bool boolean(bool v) {
    return value(ConfigNode::makeScalar(v ? "true" : "false", ConfigNode::Style::Bool, tokenPos()));
  }
  // Numbers keep the exact text the user wrote (nlohmann hands integers over as values,
  // which loses the sign of -0); the reader rounds the text once.
  bool number_integer(json::number_integer_t) { return integer(); }
  bool number_unsigned(json::number_unsigned_t) { return integer(); }
  bool number_float(json::number_float_t, const json::string_t& raw) {
    return value(ConfigNode::makeScalar(raw, ConfigNode::Style::Number, tokenPos()));
  }
  bool string(json::string_t& v) {
    return value(ConfigNode::makeScalar(v, ConfigNode::Style::String, tokenPos()));
  }
  bool binary(json::binary_t&) {
    internalError("JSON parser reported binary data in a text document");
  }
  bool start_object(std::size_t) { return open(ConfigNode::makeMap(tokenPos())); }
  bool start_array(std::size_t) { return open(ConfigNode::makeSequence(tokenPos())); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(json::string_t& k) {
    SourcePos pos = tokenPos();
    ConfigNode& map = *mStack.back();
    if (const ConfigNode* prev = map.find(k)) {
      inputError(pos.str() + ": " + messageText(path(k)) + ": duplicate key (first given at line " +
                 std::to_string(prev->keyPos.line) + ")");
    }
    mKey = k;
    mKeyPos = pos;
    return true;
  }

  bool parse_error(std::size_t position, const std::string& lastToken,
                   const nlohmann::detail::exception& ex) {
    // `position` counts characters read, so the offending one is the last of them.
    SourcePos pos = mLines.at(mFile, position > 0 ? position - 1 : 0);
    bool inMap = !mStack.empty() && mStack.back()->isMap();
    if (ex.id == 406) {
      // Number overflow (1e999): a value error, so it reads like one, at the key for a map
      // member and at the number itself in a list.
      SourcePos at = inMap ? mKeyPos : mLines.at(mFile, tokenStart());
      std::string where = messageText(path(inMap ? mKey : ""));
      inputError(at.str() + ": " + (where.empty() ? "" : where + ": ") + messageText(lastToken) +
                 " is out of range (not a finite number)");
    }
    std::string what = ex.what();
    // Drop "[json.exception.parse_error.101] parse error at line 3, column 5: " — we print
    // our own position — and the redundant "syntax error ".
    if (size_t colon = what.find(": "); colon != std::string::npos) what = what.substr(colon + 2);
    if (what.rfind("syntax error ", 0) == 0) what = what.substr(13);
    std::string where = messageText(path(inMap ? mKey : ""));
    inputError(pos.str() + ": JSON syntax error: " + what +
               (where.empty() ? "" : " (in " + where + ")"));
  }

private:
  // Start of the token just lexed: after the previous callback's token, only whitespace
  // and the separators ',' ':' (which have no callback) can come before it.
  size_t tokenStart() {
    size_t i = mScanFrom;
    while (i < mText.size() && (mText[i] == ' ' || mText[i] == '\t' || mText[i] == '\n' ||
                                mText[i] == '\r' || mText[i] == ',' || mText[i] == ':'))
      ++i;
    mScanFrom = mConsumed;
    return i;
  }
  SourcePos tokenPos() { return mLines.at(mFile, tokenStart()); }

  // An integer token is '-'? digits, so it is the run of those characters at its start.
  bool integer() {
    size_t start = tokenStart();
    size_t end = start;
    while (end < mText.size() && (mText[end] == '-' || (mText[end] >= '0' && mText[end] <= '9')))
      ++end;
    return value(ConfigNode::makeScalar(std::string(mText.substr(start, end - start)),
                                        ConfigNode::Style::Number, mLines.at(mFile, start)));
  }

  // Places a finished value; a map member takes its key's position, which is where a user
  // looks for "the setting" (and where nlohmann-style editors point).
  ConfigNode* place(ConfigNode v) {
    if (mStack.empty()) {
      mRoot = std::move(v);
      return &mRoot;
    }
    ConfigNode& parent = *mStack.back();
    if (parent.isMap()) {
      v.pos = mKeyPos;
      ConfigNode& placed = parent.add(std::move(mKey), mKeyPos, std::move(v));
      mKey.clear();  // no pending key until the next one is lexed (error messages use it)
      return &placed;
    }
    parent.children.push_back(std::move(v));
    return &parent.children.back();
  }
  bool value(ConfigNode v) {
    place(std::move(v));
    return true;
  }
  // Containers stay on the stack while open. Pointers into parents' child vectors are
  // safe: a parent gains no children while one of its children is open.
  bool open(ConfigNode v) {
    mStack.push_back(place(std::move(v)));
    return true;
  }
  bool close() {
    mScanFrom = mConsumed;
    mStack.pop_back();
    return true;
  }

  // Key path of the value being parsed, for messages: "camera.latitude", "sky.glow_size".
  std::string path(const std::string& leaf) const {
    std::string p;
    for (size_t i = 1; i < mStack.size(); ++i) {
      const ConfigNode& parent = *mStack[i - 1];
      if (parent.isMap())
        p += (p.empty() ? "" : ".") + mStack[i]->key;
      else
        p += "[" + std::to_string(parent.children.size() - 1) + "]";
    }
    if (!leaf.empty()) p += (p.empty() ? "" : ".") + leaf;
    return p;
  }

  std::string_view mText;
  const std::string& mFile;
  const size_t& mConsumed;
  LineIndex mLines;
  size_t mScanFrom = 0;
  ConfigNode mRoot;
  std::vector<ConfigNode*> mStack;
  std::string mKey;
  SourcePos mKeyPos;
};

}  // namespace

ConfigNode parseJsonTree(std::string_view text, const std::string& sourceName) {
  size_t consumed = 0;
  TreeBuilder builder(text, sourceName, consumed);
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  nlohmann::json::sax_parse(CountingIterator(begin, begin, &consumed),
                            CountingIterator(end, begin, &consumed), &builder);
  ConfigNode root = builder.takeRoot();
  if (!root.isMap())
    inputError(root.pos.str() + ": expected an object of sections at the top level, got " +
               root.describeKind());
  return root;
}

}  // namespace sky
