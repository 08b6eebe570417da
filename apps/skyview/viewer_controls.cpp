// The viewer's controls: keys, mouse look, the time-lapse clock and the script commands,
// which press the same keys and set the same scene keys a person would.
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <utility>

#include "engine/core/error.h"
#include "imgui_layer.h"
#include "viewer.h"

namespace sky::view {

namespace {

constexpr double kMetresPerDegree = 111320.0;  // along a meridian, near enough for a viewer
constexpr double kMoveMs = 200.0;              // W A S D, metres per second
constexpr double kClimbMs = 100.0;             // Q E
constexpr double kFastFactor = 10.0;           // with Shift
constexpr double kScriptKeySeconds = 0.5;      // a scripted movement key: half a second held
constexpr double kLookDegPerPixel = 0.15;      // at vertical_fov 60

struct NamedKey {
  const char* name;
  int key;
};

constexpr NamedKey kNamedKeys[] = {
    {"tab", GLFW_KEY_TAB},
    {"space", GLFW_KEY_SPACE},
    {"escape", GLFW_KEY_ESCAPE},
    {"esc", GLFW_KEY_ESCAPE},
    {"enter", GLFW_KEY_ENTER},
    {"left", GLFW_KEY_LEFT},
    {"right", GLFW_KEY_RIGHT},
    {"up", GLFW_KEY_UP},
    {"down", GLFW_KEY_DOWN},
    {"[", GLFW_KEY_LEFT_BRACKET},
    {"]", GLFW_KEY_RIGHT_BRACKET},
    {",", GLFW_KEY_COMMA},
    {".", GLFW_KEY_PERIOD},
    {"-", GLFW_KEY_MINUS},
    {"=", GLFW_KEY_EQUAL},
    {"left_bracket", GLFW_KEY_LEFT_BRACKET},
    {"right_bracket", GLFW_KEY_RIGHT_BRACKET},
    {"comma", GLFW_KEY_COMMA},
    {"period", GLFW_KEY_PERIOD},
    {"minus", GLFW_KEY_MINUS},
    {"equal", GLFW_KEY_EQUAL},
};

// "ctrl+s", "F12", "shift+tab": the GLFW key and modifiers, or key -1.
std::pair<int, int> parseKeyName(std::string name) {
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  int mods = 0;
  for (auto [prefix, bit] : {std::pair<const char*, int>{"ctrl+", GLFW_MOD_CONTROL},
                             {"shift+", GLFW_MOD_SHIFT},
                             {"alt+", GLFW_MOD_ALT}}) {
    const std::string p = prefix;
    while (name.rfind(p, 0) == 0 && name.size() > p.size()) {
      mods |= bit;
      name = name.substr(p.size());
    }
  }
  if (name.size() == 1 && std::isalpha(static_cast<unsigned char>(name[0])))
    return {GLFW_KEY_A + (name[0] - 'a'), mods};
  if (name.size() == 1 && std::isdigit(static_cast<unsigned char>(name[0])))
    return {GLFW_KEY_0 + (name[0] - '0'), mods};
  if (name.size() >= 2 && name[0] == 'f' &&
      std::all_of(name.begin() + 1, name.end(), [](char c) { return std::isdigit(c); })) {
    const int n = std::stoi(name.substr(1));
    if (n >= 1 && n <= 25) return {GLFW_KEY_F1 + n - 1, mods};
  }
  for (const NamedKey& k : kNamedKeys)
    if (name == k.name) return {k.key, mods};
  return {-1, 0};
}

double wrapDegrees(double d) {
  d = std::fmod(d, 360.0);
  return d < 0 ? d + 360.0 : d;
}

}  // namespace

void Viewer::moveCamera(double forwardM, double rightM, double upM) {
  CameraSettings& c = mScene.camera;
  const double h = c.heading * M_PI / 180.0;
  // heading is clockwise from north: forward is (north cos h, east sin h), right a quarter on.
  const double northM = forwardM * std::cos(h) - rightM * std::sin(h);
  const double eastM = forwardM * std::sin(h) + rightM * std::cos(h);
  c.latitude = std::clamp(c.latitude + northM / kMetresPerDegree, -89.9, 89.9);
  const double cosLat = std::max(std::cos(c.latitude * M_PI / 180.0), 1e-3);
  c.longitude = wrapDegrees(c.longitude + eastM / (kMetresPerDegree * cosLat) + 180.0) - 180.0;
  c.altitudeM = std::clamp(c.altitudeM + upM, -500.0, 100000.0);
  mDirty = true;
}

void Viewer::handleInput(double dt) {
  GLFWwindow* w = mWindow->handle();
  const bool imguiMouse = mImgui && mImgui->wantsMouse();
  const bool imguiKeys = mImgui && mImgui->wantsKeyboard();
  for (const KeyPress& k : mWindow->takeKeyPresses())
    if (!imguiKeys) handleKey(k.key, k.mods, false);

  // Mouse look: a drag that starts on the frame, not on the panel.
  double x = 0, y = 0;
  glfwGetCursorPos(w, &x, &y);
  const bool down = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  if (down && !mDragging && !imguiMouse) mDragging = true;
  if (!down) mDragging = false;
  if (mDragging && (x != mDragX || y != mDragY)) {
    const double scale = kLookDegPerPixel * mScene.camera.verticalFov / 60.0;
    mScene.camera.heading = wrapDegrees(mScene.camera.heading - (x - mDragX) * scale);
    mScene.camera.pitch = std::clamp(mScene.camera.pitch + (y - mDragY) * scale, -89.0, 89.0);
    mDirty = true;
  }
  mDragX = x;
  mDragY = y;

  // Held movement keys, by the frame's time.
  if (!imguiKeys) {
    const bool fast =
        mWindow->keyDown(GLFW_KEY_LEFT_SHIFT) || mWindow->keyDown(GLFW_KEY_RIGHT_SHIFT);
    const double f = fast ? kFastFactor : 1.0;
    auto axis = [&](int plus, int minus) {
      return (mWindow->keyDown(plus) ? 1.0 : 0.0) - (mWindow->keyDown(minus) ? 1.0 : 0.0);
    };
    const double forward = axis(GLFW_KEY_W, GLFW_KEY_S), right = axis(GLFW_KEY_D, GLFW_KEY_A),
                 up = axis(GLFW_KEY_E, GLFW_KEY_Q);
    if (forward != 0 || right != 0 || up != 0)
      moveCamera(forward * kMoveMs * f * dt, right * kMoveMs * f * dt, up * kClimbMs * f * dt);
  }
  if (mPanPerFrame != 0.0) {
    mScene.camera.heading = wrapDegrees(mScene.camera.heading + mPanPerFrame);
    mDirty = true;
  }
}

void Viewer::handleKey(int key, int mods, bool fromScript) {
  const bool shift = mods & GLFW_MOD_SHIFT, ctrl = mods & GLFW_MOD_CONTROL;
  const double f = shift ? kFastFactor : 1.0;
  // Movement keys act while held (handleInput); a scripted press moves by half a second's worth.
  const double step = fromScript ? kScriptKeySeconds * f : 0.0;
  switch (key) {
    case GLFW_KEY_W:
      return step ? moveCamera(kMoveMs * step, 0, 0) : void();
    case GLFW_KEY_A:
      return step ? moveCamera(0, -kMoveMs * step, 0) : void();
    case GLFW_KEY_D:
      return step ? moveCamera(0, kMoveMs * step, 0) : void();
    case GLFW_KEY_Q:
      return step ? moveCamera(0, 0, -kClimbMs * step) : void();
    case GLFW_KEY_E:
      return step ? moveCamera(0, 0, kClimbMs * step) : void();
    case GLFW_KEY_S:
      if (ctrl) {
        try {
          saveScene(mOptions.savePath.value_or(mOptions.outDir / (mScene.output.name + ".yaml")));
        } catch (const Error& e) {
          // A person sees the message and can fix the folder; a script stops on it.
          say(std::string("saving the scene failed: ") + e.what());
          if (fromScript) throw;
        }
      } else if (step)
        moveCamera(-kMoveMs * step, 0, 0);
      return;
    case GLFW_KEY_LEFT_BRACKET:
    case GLFW_KEY_RIGHT_BRACKET:
      mScene.time.start = mScene.time.start.plusSeconds(
          (key == GLFW_KEY_LEFT_BRACKET ? -1.0 : 1.0) * (shift ? 3600.0 : 900.0));
      mDirty = true;
      return;
    case GLFW_KEY_COMMA:
    case GLFW_KEY_PERIOD:
      mScene.time.start = mScene.time.start.plusSeconds(key == GLFW_KEY_COMMA ? -86400.0 : 86400.0);
      mDirty = true;
      return;
    case GLFW_KEY_SPACE:
      mPanel.playing = !mPanel.playing;
      say(mPanel.playing ? "time-lapse playing" : "time-lapse paused");
      return;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_EQUAL:
      mPanel.speed = std::clamp(mPanel.speed * (key == GLFW_KEY_MINUS ? 0.5 : 2.0), 1.0, 86400.0);
      say("time-lapse speed " + std::to_string(static_cast<long long>(mPanel.speed)) +
          " scene s per s");
      return;
    case GLFW_KEY_F12:
    case GLFW_KEY_P:
      try {
        screenshot();
      } catch (const Error& e) {
        say(std::string("screenshot failed: ") + e.what());
        if (fromScript) throw;
      }
      return;
    case GLFW_KEY_TAB:
      // The frame reads the image it shows back: a new selection renders again.
      if (shift)
        mDebug.hide();
      else
        say(mDebug.next());
      mDirty = true;
      return;
    case GLFW_KEY_V:
      say(mDebug.toggleLayout());
      mDirty = true;
      return;
    case GLFW_KEY_F1:
    case GLFW_KEY_H:
      mPanelVisible = !mPanelVisible;
      return;
    case GLFW_KEY_ESCAPE:
      mQuit = true;
      return;
    default:
      return;
  }
}

void Viewer::advanceTime(double dt) {
  if (!mPanel.playing) return;
  mScene.time.start = mScene.time.start.plusSeconds(mPanel.speed * dt);
  mDirty = true;
}

void Viewer::runScriptCommand(const ScriptCommand& c) {
  switch (c.op) {
    case ScriptOp::Wait:
      return;  // Script::step() does the waiting
    case ScriptOp::Pan:
      mPanPerFrame = c.number;
      return;
    case ScriptOp::Key: {
      const auto [key, mods] = parseKeyName(c.argument);
      if (key < 0) inputError("script: '" + c.text + "': unknown key name");
      handleKey(key, mods, true);
      return;
    }
    case ScriptOp::Screenshot:
      handleKey(GLFW_KEY_F12, 0, true);
      return;
    case ScriptOp::Set:
      applySet(c.argument);
      return;
    case ScriptOp::SaveScene:
      saveScene(c.argument);
      return;
    case ScriptOp::DumpDebug:
      dumpDebug(c.argument);
      say("wrote " + c.argument);
      return;
    case ScriptOp::DumpFrame:
      dumpFrame(c.argument);
      say("wrote " + c.argument);
      return;
    case ScriptOp::Resize:
      mWindow->resize(c.width, c.height);
      return;
    case ScriptOp::Iconify:
      mWindow->iconify();
      return;
    case ScriptOp::Restore:
      mWindow->restore();
      return;
    case ScriptOp::Quit:
      mQuit = true;
      return;
  }
}

}  // namespace sky::view
