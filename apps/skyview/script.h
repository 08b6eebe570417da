#pragma once
// --script / --script-file: commands a test or a benchmark runs at frame boundaries, e.g.
// "wait 2; pan 0.5; wait 10; screenshot; quit". The whole text is checked before the window
// opens, so a typo is a one-line BadInput error, not a surprise ten frames in.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sky::view {

enum class ScriptOp {
  Wait,          // wait N: let N frames pass
  Pan,           // pan DEG: turn the camera by DEG degrees of heading every frame from now on
  Key,           // key NAME: a key press ("F12", "ctrl+s", "tab", "w", ...)
  Screenshot,    // screenshot: as F12
  Set,           // set KEY=VALUE: a scene key, as skyrender's --set
  SaveScene,     // save-scene PATH
  DumpFrame,     // dump-frame PATH: the frame on screen as a PNG (its 8-bit codes, no dither)
  DumpDebug,     // dump-debug PATH: the debug view's image on screen as a PNG
  Resize,        // resize W H: the window's size
  Iconify,       // iconify: minimise (and treat the framebuffer as 0 x 0 until restore)
  Restore,       // restore
  Quit,          // quit
};

struct ScriptCommand {
  ScriptOp op;
  std::string text;           // the command as written, for messages
  std::string argument;       // Key, Set, SaveScene, DumpFrame, DumpDebug
  double number = 0.0;        // Wait (frames), Pan (degrees per frame)
  int width = 0, height = 0;  // Resize
};

class Script {
public:
  Script() = default;
  // Commands separated by ';' or new lines; '#' starts a comment. BadInput naming `source`
  // ("--script", or the file) and the command for anything unknown or malformed.
  static Script parse(std::string_view text, const std::string& source);

  // Called once per frame boundary: the commands to run now, i.e. everything up to the next
  // `wait N`, which then lets N boundaries pass with nothing.
  std::vector<ScriptCommand> step();
  bool done() const { return mNext >= mCommands.size() && mWaiting == 0; }
  bool empty() const { return mCommands.empty(); }

private:
  std::vector<ScriptCommand> mCommands;
  size_t mNext = 0;
  int64_t mWaiting = 0;
};

}  // namespace sky::view
