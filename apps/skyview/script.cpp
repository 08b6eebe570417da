#include "script.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "engine/core/error.h"

namespace sky::view {

namespace {

std::string trim(std::string_view s) {
  const size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  const size_t e = s.find_last_not_of(" \t\r");
  return std::string(s.substr(b, e - b + 1));
}

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

double number(const std::string& text, const std::string& where) {
  double v = 0.0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    inputError(where + ": '" + text + "' is not a number");
  return v;
}

ScriptCommand parseCommand(const std::string& text, const std::string& source) {
  const std::string where = source + ": '" + text + "'";
  const std::vector<std::string> w = words(text);
  const std::string& name = w[0];
  auto args = [&](size_t n) {
    if (w.size() != n + 1)
      inputError(where + ": " + name + " takes " + std::to_string(n) + " argument" +
                 (n == 1 ? "" : "s"));
  };
  // The rest of the line after the name, so a path or a value may contain spaces.
  const std::string rest = trim(std::string_view(text).substr(name.size()));
  ScriptCommand c{ScriptOp::Quit, text, {}, 0.0, 0, 0};
  if (name == "wait") {
    args(1);
    c.op = ScriptOp::Wait;
    c.number = number(w[1], where);
    if (c.number < 0 || c.number != std::floor(c.number))
      inputError(where + ": wait takes a whole number of frames");
  } else if (name == "pan") {
    args(1);
    c.op = ScriptOp::Pan;
    c.number = number(w[1], where);
  } else if (name == "key") {
    args(1);
    c.op = ScriptOp::Key;
    c.argument = w[1];
  } else if (name == "screenshot") {
    args(0);
    c.op = ScriptOp::Screenshot;
  } else if (name == "set") {
    if (rest.find('=') == std::string::npos) inputError(where + ": expected set KEY=VALUE");
    c.op = ScriptOp::Set;
    c.argument = rest;
  } else if (name == "save-scene" || name == "dump-frame" || name == "dump-debug") {
    if (rest.empty()) inputError(where + ": " + name + " takes a path");
    c.op = name == "save-scene"   ? ScriptOp::SaveScene
           : name == "dump-frame" ? ScriptOp::DumpFrame
                                  : ScriptOp::DumpDebug;
    c.argument = rest;
  } else if (name == "resize") {
    args(2);
    c.op = ScriptOp::Resize;
    const double width = number(w[1], where), height = number(w[2], where);
    if (width < 1 || height < 1 || width > 16384 || height > 16384 || width != std::floor(width) ||
        height != std::floor(height))
      inputError(where + ": resize takes a width and a height in whole pixels, 1..16384");
    c.width = static_cast<int>(width);
    c.height = static_cast<int>(height);
  } else if (name == "iconify" || name == "restore" || name == "quit") {
    args(0);
    c.op = name == "iconify"   ? ScriptOp::Iconify
           : name == "restore" ? ScriptOp::Restore
                               : ScriptOp::Quit;
  } else {
    inputError(where +
               ": unknown command (commands: wait, pan, key, screenshot, set, save-scene, "
               "dump-frame, dump-debug, resize, iconify, restore, quit)");
  }
  return c;
}

}  // namespace

Script Script::parse(std::string_view text, const std::string& source) {
  Script s;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find_first_of(";\n", start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view piece = text.substr(start, end - start);
    if (size_t hash = piece.find('#'); hash != std::string_view::npos)
      piece = piece.substr(0, hash);
    const std::string command = trim(piece);
    if (!command.empty()) s.mCommands.push_back(parseCommand(command, source));
    start = end + 1;
  }
  return s;
}

std::vector<ScriptCommand> Script::step() {
  std::vector<ScriptCommand> now;
  if (mWaiting > 0) {
    --mWaiting;
    return now;
  }
  while (mNext < mCommands.size()) {
    const ScriptCommand& c = mCommands[mNext++];
    if (c.op == ScriptOp::Wait) {
      // This boundary is the first of the N frames that pass.
      mWaiting = static_cast<int64_t>(c.number) - 1;
      if (mWaiting >= 0) break;
      mWaiting = 0;
      continue;
    }
    now.push_back(c);
    if (c.op == ScriptOp::Quit) break;
  }
  return now;
}

}  // namespace sky::view
