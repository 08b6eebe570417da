#pragma once
// skyview's command line: strict, like skyrender's (every unknown or malformed argument is a
// one-line BadInput error), and its help text.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "script.h"

namespace sky::view {

struct ViewerOptions {
  std::optional<std::filesystem::path> scenePath;  // none: the embedded default scene
  std::vector<std::string> overrides;              // --set KEY=VALUE, in order
  std::filesystem::path outDir = "out";            // screenshots
  std::optional<std::filesystem::path> savePath;   // Ctrl+S; default outDir/<output.name>.yaml
  int width = 640, height = 360;                   // the window's initial size
  double renderScale = 1.0;                        // render size / framebuffer size
  std::optional<int64_t> frames;                   // quit after this many frames
  Script script;
  bool reportFps = false;
  bool logFrames = false;  // one stdout line per frame (tests follow a running window by it)
  bool panel = true;
  std::string gpu;
  std::optional<std::filesystem::path> ocio;
  bool help = false;
};

// BadInput naming the argument for anything wrong.
ViewerOptions parseViewerOptions(const std::vector<std::string>& args);
// The --help page: usage, options, keys and script commands (docs/skyview.md has more).
const char* viewerHelpText();

}  // namespace sky::view
