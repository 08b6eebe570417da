#pragma once
// The viewer: one window, one Renderer, one scene that the panel, the keys, the mouse, a
// script and the scene file's hot reload all edit. A frame renders only when something changed
// (or the time-lapse plays, or the camera pans); otherwise the last image is presented again.
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/common/stop_signals.h"
#include "debug_panel.h"
#include "engine/color/ocio_output.h"
#include "engine/graph/frame_graph.h"
#include "engine/render/exposure.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene.h"
#include "file_watcher.h"
#include "panel.h"
#include "viewer_options.h"
#include "window.h"

namespace sky {
class Context;
class Renderer;
class ShaderCompiler;
}  // namespace sky

namespace sky::view {

class ImguiLayer;
class Presenter;
class Swapchain;

class Viewer {
public:
  // Loads the scene and checks it and the options (BadInput), then opens the window and
  // the Vulkan device (Internal error without a display).
  explicit Viewer(ViewerOptions options);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // Runs until the window closes, Esc, a script's quit, --frames or SIGINT/SIGTERM.
  int run();

private:
  // viewer.cpp: frames, rendering, reloads, files.
  bool frame(double dt);
  void renderView();
  // The GPU device was lost: keep the window (and the last frame in it) with the message in
  // its title and on stdout, draw nothing more, and exit 1 once it is closed.
  void stopDrawing(const std::string& message);
  RenderedFrame renderWith(Renderer& renderer);
  void show(RenderedFrame& frame);
  void pollReloads();
  void reloadShaders();
  void reloadScene();
  void screenshot();
  void saveScene(const std::filesystem::path& path);
  void dumpFrame(const std::filesystem::path& path);
  void dumpDebug(const std::filesystem::path& path) const;
  void applySet(const std::string& assignment);
  void drawUi();
  // Prints one line (stdout) and shows it in the window.
  void say(const std::string& line);
  // viewer_controls.cpp: keys, mouse, script commands, the clock.
  void handleInput(double dt);
  void handleKey(int key, int mods, bool fromScript);
  void runScriptCommand(const ScriptCommand& command);
  void moveCamera(double forwardM, double rightM, double upM);
  void advanceTime(double dt);

  ViewerOptions mOptions;
  std::optional<StopSignals> mStop;  // from the start of run()
  OcioOutput mOcio;
  Scene mScene;     // what the window shows (its time an instant)
  Scene mLastGood;  // the last scene that rendered, to fall back to
  Script mScript;

  std::unique_ptr<Window> mWindow;
  std::unique_ptr<Context> mCtx;
  std::unique_ptr<WindowSurface> mSurface;
  std::unique_ptr<ShaderCompiler> mCompiler;
  std::unique_ptr<Renderer> mRenderer;
  std::unique_ptr<Swapchain> mSwapchain;
  std::unique_ptr<Presenter> mPresenter;
  std::unique_ptr<ImguiLayer> mImgui;

  FileWatcher mShaderWatch;
  FileWatcher mSceneWatch;
  DebugPanel mDebug;
  uint64_t mTileRevision = ~0ull;
  PanelState mPanel;
  bool mPanelVisible = true;

  // The frame on screen: the presenter's frame image holds it (the renderer writes it there
  // on the GPU); only its size is kept here.
  bool mHasFrame = false;
  uint32_t mDisplayW = 0, mDisplayH = 0;
  std::vector<PassTiming> mPasses;
  double mRenderMs = 0.0;
  ExposureMeter mMeter;  // the CPU display path (histogram exposure)

  bool mDirty = true;  // the scene changed since the frame on screen
  bool mRecreate = true;
  VkExtent2D mSwapchainFor{0, 0};
  bool mQuit = false;
  double mPanPerFrame = 0.0;
  bool mDragging = false;
  double mDragX = 0.0, mDragY = 0.0;

  std::string mShaderError, mSceneError, mRenderError, mStatus;
  std::string mStopped;  // why nothing is drawn any more (a lost device); empty while drawing
  int64_t mFrames = 0, mPresented = 0, mRendered = 0;
  double mRenderMsTotal = 0.0;
  double mFps = 0.0;
};

}  // namespace sky::view
