#include "viewer.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/common/debug_view.h"
#include "apps/common/default_scene.h"
#include "apps/common/stop_signals.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/paths.h"
#include "engine/gpu/context.h"
#include "engine/io/png.h"
#include "engine/render/render_files.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"
#include "imgui_layer.h"
#include "presenter.h"
#include "swapchain.h"

namespace sky::view {
namespace fs = std::filesystem;

namespace {

// Library messages may hold new lines; every line skyview prints is one line.
std::string oneLine(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

// The viewer shows one instant: a time-lapse file opens at its first frame (Space plays on).
void makeInstant(Scene& scene) {
  scene.time.end.reset();
  scene.time.stepSeconds = 0.0;
}

// A scene as the window opens it: one instant, and the clouds of each frame reused by the
// next (clouds.temporal.mode on). A window is a sequence; reuse is what makes a pan run at
// interactive rates on lavapipe, and the first frame (and any after a cut) is the full march,
// so a saved scene still renders as the window's still. The panel can switch it off.
Scene windowScene(Scene scene) {
  makeInstant(scene);
  scene.clouds.temporal.mode = CloudTemporalMode::On;
  return scene;
}

Scene loadStartScene(const ViewerOptions& o) {
  return windowScene(o.scenePath ? loadSceneFile(*o.scenePath, o.overrides)
                                 : loadSceneText(skyDefaultSceneText(), ConfigFormat::Yaml,
                                                 "<default scene>", o.overrides));
}

}  // namespace

Viewer::Viewer(ViewerOptions options)
    : mOptions(std::move(options)),
      mOcio(OcioOutput::load(mOptions.ocio)),
      mScene(loadStartScene(mOptions)),
      mLastGood(mScene),
      mScript(mOptions.script) {
  mOcio.checkDisplayView(mScene.output.display, mScene.output.view);
  mPanel.renderScale = mOptions.renderScale;
  mPanelVisible = mOptions.panel;

  mWindow = std::make_unique<Window>(mOptions.width, mOptions.height, "skyview");
  ContextOptions co = ContextOptions::fromEnvironment();
  co.gpu = mOptions.gpu;
  co.instanceExtensions = Window::requiredInstanceExtensions();
  co.deviceExtensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  mCtx = std::make_unique<Context>(co);
  mSurface = std::make_unique<WindowSurface>(*mWindow, mCtx->instance());
  mCompiler = std::make_unique<ShaderCompiler>();
  mRenderer = std::make_unique<Renderer>(*mCtx, *mCompiler);
  mSwapchain = std::make_unique<Swapchain>(*mCtx, mSurface->handle());
  mPresenter = std::make_unique<Presenter>(*mCtx, *mSwapchain);

  mShaderWatch = FileWatcher(mCompiler->root());
  if (mOptions.scenePath) mSceneWatch = FileWatcher(*mOptions.scenePath);
}

Viewer::~Viewer() {
  // The members go in reverse order (ImGui, presenter, swapchain, renderer, surface, device,
  // window); the GPU must be done with all of them first.
  if (mCtx) vkDeviceWaitIdle(mCtx->device());
}

void Viewer::say(const std::string& line) {
  mStatus = oneLine(line);
  std::printf("skyview: %s\n", mStatus.c_str());
  std::fflush(stdout);
}

int Viewer::run() {
  // SIGINT/SIGTERM close the window the way its close button does: the frame in hand is
  // finished, everything is destroyed in order; a second request kills (stop_signals.h).
  mStop.emplace();
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto last = start;
  // The rate once the first frame is on screen: the first marches every pixel (and may bake
  // or compile), the ones after are what a person panning sees.
  std::optional<Clock::time_point> steadyStart;
  int64_t steadyFrom = 0;
  while (!mQuit) {
    const auto now = Clock::now();
    const double dt = std::min(std::chrono::duration<double>(now - last).count(), 0.5);
    last = now;
    if (!frame(dt)) break;
    ++mFrames;
    if (!steadyStart && mPresented > 0) {
      steadyStart = Clock::now();
      steadyFrom = mPresented;
    }
    if (mOptions.frames && mFrames >= *mOptions.frames) break;
  }
  if (mCtx) vkDeviceWaitIdle(mCtx->device());  // a lost device answers at once
  const auto end = Clock::now();
  const double seconds = std::chrono::duration<double>(end - start).count();
  if (mOptions.reportFps) {
    const double steadySeconds =
        steadyStart ? std::chrono::duration<double>(end - *steadyStart).count() : 0.0;
    const int64_t steadyFrames = mPresented - steadyFrom;
    std::printf(
        "skyview: %lld frames in %.1f s, %.1f fps (render %.0f ms/frame, %lld rendered); after "
        "the first: %.2f fps\n",
        static_cast<long long>(mPresented), seconds,
        seconds > 0 ? static_cast<double>(mPresented) / seconds : 0.0,
        mRendered ? mRenderMsTotal / static_cast<double>(mRendered) : 0.0,
        static_cast<long long>(mRendered),
        steadySeconds > 0 ? static_cast<double>(steadyFrames) / steadySeconds : 0.0);
  }
  std::fflush(stdout);
  if (!mStopped.empty()) {
    std::fprintf(stderr, "skyview: %s\n", mStopped.c_str());
    return 1;
  }
  return 0;
}

void Viewer::stopDrawing(const std::string& message) {
  mStopped = oneLine(message);
  say(mStopped + "; nothing more is drawn, the window stays open until closed");
  glfwSetWindowTitle(mWindow->handle(), ("skyview: stopped: " + mStopped).c_str());
}

bool Viewer::frame(double dt) {
  // A script or a frame limit runs as fast as it can; a person's window sleeps while
  // nothing changes (hot reload still polls twice a second).
  const bool scripted = !mScript.empty() || mOptions.frames.has_value();
  const bool busy = mDirty || mPanel.playing || mPanPerFrame != 0.0 || mDragging;
  if (scripted || busy || mRecreate)
    glfwPollEvents();
  else
    glfwWaitEventsTimeout(0.25);
  if (mWindow->closeRequested() || (mStop && mStop->signal())) return false;

  if (!mStopped.empty()) {
    // Nothing can run on a lost device: the window keeps its last frame and the title says
    // why. A script still runs (to its quit), a person closes the window.
    for (const ScriptCommand& c : mScript.step()) {
      if (c.op == ScriptOp::Quit) return false;
    }
    if (!scripted) glfwWaitEventsTimeout(0.25);
    return true;
  }
  pollReloads();
  for (const ScriptCommand& c : mScript.step()) {
    runScriptCommand(c);
    if (mQuit) return false;
  }
  handleInput(dt);
  if (mQuit) return false;
  advanceTime(dt);

  const VkExtent2D fb = mWindow->framebufferSize();
  if (fb.width == 0 || fb.height == 0) {
    // Minimised: nothing to draw into and no swapchain to make; wait for the window to come
    // back (briefly under a script, so its frame count keeps moving).
    glfwWaitEventsTimeout(scripted ? 0.01 : 0.25);
    return true;
  }
  if (mRecreate || fb.width != mSwapchainFor.width || fb.height != mSwapchainFor.height) {
    if (!mSwapchain->recreate(fb)) return true;
    mSwapchainFor = fb;
    mRecreate = false;
    if (mImgui)
      mImgui->swapchainRecreated(*mSwapchain);
    else
      mImgui = std::make_unique<ImguiLayer>(*mCtx, *mWindow, *mSwapchain);
  }

  const VkExtent2D target = mSwapchain->extent();
  const uint32_t renderW = std::clamp<uint32_t>(
      static_cast<uint32_t>(std::lround(target.width * mPanel.renderScale)), 1, 16384);
  const uint32_t renderH = std::clamp<uint32_t>(
      static_cast<uint32_t>(std::lround(target.height * mPanel.renderScale)), 1, 16384);
  if (renderW != static_cast<uint32_t>(mScene.output.width) ||
      renderH != static_cast<uint32_t>(mScene.output.height)) {
    mScene.output.width = static_cast<int>(renderW);
    mScene.output.height = static_cast<int>(renderH);
    mDirty = true;
  }
  if (mDirty) renderView();
  // A device lost in that render: nothing more is drawn, this frame neither (presenting it
  // logged one more frame after the message saying the drawing had stopped).
  if (!mStopped.empty()) return true;

  if (mDebug.revision() != mTileRevision) {
    mTileRevision = mDebug.revision();
    if (const DebugTile* t = mDebug.current())
      mPresenter->setTile(t->rgba.data(), t->width, t->height);
  }
  mImgui->beginFrame();
  drawUi();
  const DebugPlacement placement = mDebug.place(target.width, target.height, mDisplayW, mDisplayH);
  try {
    if (mPresenter->present(placement, [&](VkCommandBuffer cmd) { mImgui->draw(cmd); }) ==
        PresentStatus::Recreate)
      mRecreate = true;
  } catch (const DeviceLost& e) {
    stopDrawing(e.what());
    return true;
  }
  ++mPresented;
  if (dt > 0) mFps = 0.9 * mFps + 0.1 / dt;
  if (mOptions.logFrames) {
    std::printf("skyview: frame %lld (%ux%u, %lld rendered)\n", static_cast<long long>(mFrames),
                target.width, target.height, static_cast<long long>(mRendered));
    std::fflush(stdout);
  }
  return true;
}

RenderedFrame Viewer::renderWith(Renderer& renderer) {
  RenderOptions options;
  // The GPU display path gives the 8-bit picture straight away; a histogram exposure meters
  // the frame on the CPU, so it reads back the beauty and takes skyrender's path.
  const bool histogram = mScene.output.exposure == ExposureMode::Histogram;
  options.readBack = histogram ? ReadBack::Beauty : ReadBack::Display;
  options.gpuDisplay = histogram ? nullptr : &mOcio;
  // The GPU path writes the frame straight into the image the window blits from: nothing
  // comes back to the host and nothing is uploaded (after the last present has read it).
  if (!histogram)
    options.displayTarget = &mPresenter->frameTarget(static_cast<uint32_t>(mScene.output.width),
                                                     static_cast<uint32_t>(mScene.output.height));
  options.displayTargetLayout = WindowImage::kLayout;
  // The debug view's image comes back with the frame, by its name in the frame's graph.
  if (const std::optional<std::string> wanted = mDebug.wanted()) options.debugOutputs = {*wanted};
  try {
    return renderer.render(mScene, mScene.time.start, options);
  } catch (const UnknownImageName&) {
    // The scene changed under the debug view (no clouds any more, another sky model): the
    // frame without it, and show() moves the selection to an image the frame has.
    options.debugOutputs.clear();
    return renderer.render(mScene, mScene.time.start, options);
  }
}

void Viewer::show(RenderedFrame& frame) {
  mLastGood = mScene;
  mDisplayW = static_cast<uint32_t>(mScene.output.width);
  mDisplayH = static_cast<uint32_t>(mScene.output.height);
  if (mScene.output.exposure == ExposureMode::Histogram) {
    const FrameExposure exposure = mMeter.expose(mScene, frame, mScene.time.start);
    const std::vector<float> px = displayPixels(frame, mScene, exposure, mOcio);
    std::vector<uint8_t> codes(px.size());
    for (size_t i = 0; i < px.size(); ++i)
      codes[i] = static_cast<uint8_t>(std::lround(std::clamp(px[i], 0.0f, 1.0f) * 255.0f));
    mPresenter->setFrame(codes.data(), mDisplayW, mDisplayH);
  } else {
    mPresenter->frameDrawn();
  }
  mHasFrame = true;
  if (!frame.debug.empty()) {
    const DebugImage& d = frame.debug.front();
    const DisplayTile shown = debugDisplay(d);
    // "cloud_steps  (volumetric_clouds, 182.31 ms; heat 0..208)", as the contact sheet says.
    char detail[160];
    if (d.info.pass.empty())
      std::snprintf(detail, sizeof detail, "imported; %s", debugViewName(d.info.view));
    else
      std::snprintf(detail, sizeof detail, "%s, %.2f ms; %s", d.info.pass.c_str(), d.gpuMs,
                    debugViewName(d.info.view));
    std::string caption = d.info.name + "  (" + detail;
    if (shown.legend) {
      char range[96];
      std::snprintf(range, sizeof range, " %.4g..%.4g%s", double(shown.low), double(shown.high),
                    shown.unit);
      caption += range;
    }
    mDebug.setTile({caption + ")", shown.width, shown.height, shown.rgba});
  }
  // A selection the new frame lacks moves to one it has: fetch that with the next frame.
  if (mDebug.setImages(frame.images)) mDirty = true;
  mPasses = frame.frame.passes;
  mRenderMs = frame.frame.wallMs;
  mRenderMsTotal += frame.frame.wallMs;
  ++mRendered;
}

void Viewer::renderView() {
  mDirty = false;
  RenderedFrame frame;
  try {
    frame = renderWith(*mRenderer);
  } catch (const DeviceLost& e) {
    if (!mHasFrame) throw;  // no window content yet: the one-line error and exit 1
    stopDrawing(e.what());
    return;
  } catch (const Error& e) {
    // A setting the renderer refuses (a size too large, a shader variant that does not
    // compile): back to the last scene that rendered; the frame on screen stays.
    if (!mHasFrame) throw;
    mRenderError = "render failed: " + oneLine(e.what());
    say(mRenderError);
    const int w = mScene.output.width, h = mScene.output.height;
    mScene = mLastGood;
    mScene.output.width = w;
    mScene.output.height = h;
    return;
  }
  mRenderError.clear();
  show(frame);
}

void Viewer::pollReloads() {
  if (mShaderWatch.poll()) reloadShaders();
  if (mSceneWatch.poll()) reloadScene();
}

void Viewer::reloadShaders() {
  // A new Renderer builds every pipeline from the files as they are now. It replaces the old
  // one only once it has also rendered the current frame (shader variants are built on first
  // use), so a broken shader leaves the old renderer running.
  try {
    auto renderer = std::make_unique<Renderer>(*mCtx, *mCompiler);
    RenderedFrame frame = renderWith(*renderer);
    // The old renderer's last frame finished inside render(); wait anyway before its
    // pipelines and images go.
    vkDeviceWaitIdle(mCtx->device());
    mRenderer = std::move(renderer);
    mRenderError.clear();
    mDirty = false;
    show(frame);
    mShaderError.clear();
    say("shaders reloaded");
  } catch (const DeviceLost& e) {
    stopDrawing(e.what());
  } catch (const Error& e) {
    mShaderError = "shader reload failed: " + oneLine(e.what());
    say(mShaderError);
  }
}

void Viewer::reloadScene() {
  try {
    Scene scene = windowScene(loadSceneFile(*mOptions.scenePath, mOptions.overrides));
    mOcio.checkDisplayView(scene.output.display, scene.output.view);
    scene.output.width = mScene.output.width;
    scene.output.height = mScene.output.height;
    mScene = scene;
    mDirty = true;
    mSceneError.clear();
    say("scene reloaded");
  } catch (const Error& e) {
    mSceneError = "scene reload failed: " + oneLine(e.what());
    say(mSceneError);
  }
}

void Viewer::screenshot() {
  // A full render of the frame on screen with the EXR's layers, written as skyrender writes
  // a still: temporal reuse is off for it, so it is the image `skyrender render` gives.
  Scene still = mScene;
  still.clouds.temporal.mode = CloudTemporalMode::Off;
  RenderedFrame frame = mRenderer->render(still, still.time.start);
  ExposureMeter meter;
  const FrameExposure exposure = meter.expose(mScene, frame, mScene.time.start);
  fs::create_directories(mOptions.outDir);
  std::string stem;
  for (int i = 1;; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "_%04d", i);
    stem = mScene.output.name + name;
    if (!fs::exists(mOptions.outDir / (stem + ".png"))) break;
  }
  const RenderFiles files =
      writeRenderFiles(mOptions.outDir, stem, mScene, frame, exposure, mOcio, mCtx->deviceName());
  say("wrote " + files.exr.string() + ", " + files.png.string() + ", " + files.report.string());
  // The next window frame follows a different history (temporal reuse) than the still did.
  mDirty = true;
}

void Viewer::saveScene(const fs::path& path) {
  // What the window shows: its size, its instant, paths made absolute so the file renders
  // the same from wherever it is saved.
  const std::string text = writeScene(mScene.withAbsolutePaths(), formatForPath(path));
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  writeFileAtomic(path, text);
  say("saved scene " + path.string());
}

void Viewer::dumpFrame(const fs::path& path) {
  // The codes the window blits, read back from its frame image: what is on screen.
  const Presenter::Codes codes = mPresenter->readFrame();
  if (!mHasFrame || codes.rgba.empty()) inputError("dump-frame: no frame on screen yet");
  writePngCodes(path, static_cast<int>(codes.width), static_cast<int>(codes.height), codes.rgba);
}

void Viewer::dumpDebug(const fs::path& path) const {
  const DebugTile* tile = mDebug.current();
  if (!tile) inputError("dump-debug: the debug view shows no image (Tab shows one)");
  writePngCodes(path, static_cast<int>(tile->width), static_cast<int>(tile->height), tile->rgba);
}

void Viewer::applySet(const std::string& assignment) {
  // Through the scene file's own reader, exactly as skyrender's --set: the scene written out,
  // read back with the override, checked like a file.
  Scene scene = loadSceneText(writeScene(mScene.withAbsolutePaths(), ConfigFormat::Yaml),
                              ConfigFormat::Yaml, "set " + assignment, {assignment});
  mOcio.checkDisplayView(scene.output.display, scene.output.view);
  makeInstant(scene);
  scene.baseDir = mScene.baseDir;
  scene.output.width = mScene.output.width;
  scene.output.height = mScene.output.height;
  mScene = scene;
  mDirty = true;
}

void Viewer::drawUi() {
  PanelInfo info;
  info.renderWidth = mDisplayW;
  info.renderHeight = mDisplayH;
  info.renderMs = mRenderMs;
  info.fps = mFps;
  info.passes = mPasses;
  for (const std::string* e : {&mShaderError, &mSceneError, &mRenderError})
    if (!e->empty()) info.errors.push_back(*e);
  info.status = mStatus;
  const PanelActions a = drawPanel(mScene, mPanel, info, mOcio, mPanelVisible);
  if (a.sceneChanged) mDirty = true;
  if (const DebugTile* t = mDebug.current()) {
    // The caption over the debug image.
    const DebugPlacement p =
        mDebug.place(mSwapchain->extent().width, mSwapchain->extent().height, mDisplayW, mDisplayH);
    beginOverlay("##debug", static_cast<float>(p.tile.x) + 4, static_cast<float>(p.tile.y) + 4, 0,
                 0);
    ImGui::TextUnformatted(t->caption.c_str());
    ImGui::End();
  }
  // The buttons do what their keys do, errors included.
  if (a.screenshot) handleKey(GLFW_KEY_F12, 0, false);
  if (a.saveScene) handleKey(GLFW_KEY_S, GLFW_MOD_CONTROL, false);
}

}  // namespace sky::view
