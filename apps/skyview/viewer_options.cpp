#include "viewer_options.h"

#include <charconv>
#include <cmath>
#include <set>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace sky::view {

namespace {

double numberArg(const std::string& option, const std::string& text, double min, double max,
                 bool whole) {
  double v = 0.0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    inputError(option + " '" + text + "': expected a number");
  if (whole && v != std::floor(v)) inputError(option + " '" + text + "': expected a whole number");
  if (v < min || v > max)
    inputError(option + " " + text + ": out of range [" +
               std::to_string(static_cast<long long>(min)) + ", " +
               std::to_string(static_cast<long long>(max)) + "]");
  return v;
}

}  // namespace

ViewerOptions parseViewerOptions(const std::vector<std::string>& args) {
  static const std::set<std::string> kValued = {
      "--out",    "--set",         "--width", "--height", "--render-scale", "--frames",
      "--script", "--script-file", "--gpu",   "--ocio",   "--save-scene"};
  static const std::set<std::string> kFlags = {"--report-fps", "--log-frames", "--no-panel",
                                               "--help", "-h"};
  ViewerOptions o;
  std::string scriptText, scriptSource;
  for (size_t i = 0; i < args.size(); ++i) {
    std::string a = args[i];
    std::optional<std::string> value;
    if (a.rfind("--", 0) == 0 && a.find('=') != std::string::npos) {
      value = a.substr(a.find('=') + 1);
      a = a.substr(0, a.find('='));
    }
    if (kFlags.count(a)) {
      if (value) inputError(a + " takes no value");
      if (a == "--report-fps") o.reportFps = true;
      if (a == "--log-frames") o.logFrames = true;
      if (a == "--no-panel") o.panel = false;
      if (a == "--help" || a == "-h") o.help = true;
      continue;
    }
    if (kValued.count(a)) {
      if (!value) {
        if (i + 1 >= args.size()) inputError(a + " needs a value (see skyview --help)");
        value = args[++i];
      }
      const std::string& v = *value;
      if (a == "--out") o.outDir = v;
      if (a == "--save-scene") o.savePath = v;
      if (a == "--set") o.overrides.push_back(v);
      if (a == "--width") o.width = static_cast<int>(numberArg(a, v, 1, 16384, true));
      if (a == "--height") o.height = static_cast<int>(numberArg(a, v, 1, 16384, true));
      if (a == "--render-scale") {
        o.renderScale = numberArg(a, v, 0, 4, false);
        if (o.renderScale < 0.05) inputError(a + " " + v + ": must be at least 0.05");
      }
      if (a == "--frames") o.frames = static_cast<int64_t>(numberArg(a, v, 1, 1e9, true));
      if (a == "--gpu") o.gpu = v;
      if (a == "--ocio") o.ocio = v;
      if (a == "--script" || a == "--script-file") {
        if (!scriptSource.empty()) inputError("give one --script or --script-file");
        scriptSource = a == "--script" ? "--script" : v;
        scriptText = a == "--script" ? v : readTextFile(v);
      }
      continue;
    }
    if (a.rfind("-", 0) == 0 && a.size() > 1)
      inputError("unknown option '" + args[i] + "' (see skyview --help)");
    if (o.scenePath) inputError("skyview takes one scene file, got also '" + a + "'");
    o.scenePath = a;
  }
  if (!scriptSource.empty()) o.script = Script::parse(scriptText, scriptSource);
  return o;
}

const char* viewerHelpText() {
  return R"(skyview: the skylayers scene in a window, re-rendered as you change it.

usage: skyview [SCENE.yaml|json] [options]

Without a scene, the default scene (configs/default.yaml) opens. The window renders at its
own size (times --render-scale); the scene's output.width and output.height are ignored.
Frames reuse each other's clouds (clouds.temporal.mode is on in the window; the panel can
turn it off); --set clouds.temporal.resolution=half is faster still.

options:
  --set KEY=VALUE      override a scene key, as skyrender render --set (repeatable)
  --out DIR            screenshots go here (default out/)
  --save-scene FILE    where Ctrl+S saves the scene (default DIR/<output.name>.yaml)
  --width W --height H the window's size (default 640 x 360)
  --render-scale S     render at S times the window's size (default 1)
  --frames N           quit after N frames
  --script "CMD; ..."  commands run at frame boundaries (below); --script-file FILE reads them
  --report-fps         print frames, seconds and fps when the window closes
  --log-frames         print one line per frame
  --no-panel           start with the settings panel hidden (F1 shows it)
  --gpu NAME|INDEX     the Vulkan device; --ocio FILE the OCIO config

keys:
  drag (left mouse)    look around (camera.heading, camera.pitch)
  W A S D              move north/south/east/west along the view (camera.latitude/longitude)
  Q E                  down / up (camera.altitude_m); Shift: ten times faster
  [ ]                  time of day -/+ 15 minutes (Shift: 1 hour); , . date -/+ 1 day
  Space                play / pause the time-lapse; - = slower / faster
  F12 or P             screenshot: EXR, PNG and JSON as skyrender writes them, into --out
  Ctrl+S               save the scene (skyrender render FILE renders the same image)
  Tab / Shift+Tab / V  debug view: next image / hide / side by side <-> full screen
  F1 or H              show / hide the panel; Esc quits

script commands (--script): wait N, pan DEG_PER_FRAME, key NAME, screenshot, set KEY=VALUE,
  save-scene PATH, dump-frame PATH, dump-debug PATH,
  resize W H, iconify, restore, quit

Shaders (SKY_SHADER_DIR or shaders/) and the scene file are watched: an edit rebuilds the
pipelines or reloads the scene; an error is shown in the window and the last good state kept.
docs/skyview.md has the details.
)";
}

}  // namespace sky::view
