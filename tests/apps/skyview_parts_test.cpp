// skyview's parts that need no window: the script, the debug view's layout, file polling and
// the command line.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "debug_panel.h"
#include "engine/core/error.h"
#include "file_watcher.h"
#include "script.h"
#include "viewer_options.h"

namespace sky::view {
namespace {

using ::testing::HasSubstr;

std::string ops(Script& s, int boundaries) {
  std::string trace;
  for (int i = 0; i < boundaries; ++i) {
    trace += "|";
    for (const ScriptCommand& c : s.step()) trace += c.text + ";";
  }
  return trace;
}

TEST(SkyviewScript, WaitLetsFramesPass) {
  Script s = Script::parse("pan 2; wait 2; screenshot\nwait 0; key ctrl+s # save\n quit", "t");
  // wait 2: the frames of this boundary and the next pass; the third boundary goes on.
  EXPECT_EQ(ops(s, 4), "|pan 2;||screenshot;key ctrl+s;quit;|");
  EXPECT_TRUE(s.done());
}

TEST(SkyviewScript, RejectsWhatItCannotRun) {
  auto message = [](const std::string& text) {
    try {
      Script::parse(text, "--script");
    } catch (const Error& e) {
      EXPECT_EQ(e.exitCode(), 2);
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message("wait"), HasSubstr("--script: 'wait': wait takes 1 argument"));
  EXPECT_THAT(message("wait 1.5"), HasSubstr("whole number"));
  EXPECT_THAT(message("pan fast"), HasSubstr("'fast' is not a number"));
  EXPECT_THAT(message("set cover"), HasSubstr("set KEY=VALUE"));
  EXPECT_THAT(message("resize 0 10"), HasSubstr("1..16384"));
  EXPECT_THAT(message("explode"), HasSubstr("unknown command"));
}

DebugImageInfo info(const char* name, uint32_t width, uint32_t height) {
  DebugImageInfo i;
  i.name = name;
  i.width = width;
  i.height = height;
  return i;
}

DebugTile tile(const char* name, uint32_t width, uint32_t height) {
  return {name, width, height, std::vector<uint8_t>(size_t(width) * height * 4)};
}

// The debug view steps through the frame's images by name, asks the next frame for the one
// it shows, and places the frame and that image side by side or full screen.
TEST(SkyviewDebugPanel, FollowsTheFramesImagesAndPlacesFrameAndTile) {
  DebugPanel v;
  EXPECT_EQ(v.next(), "no debug resources");
  EXPECT_EQ(v.layout(), DebugLayout::Hidden);
  // Hidden: the frame fills the window, and no image is read back.
  EXPECT_EQ(v.place(640, 360, 320, 180).frame, (Rect{0, 0, 640, 360}));
  EXPECT_FALSE(v.setImages({info("a", 100, 100), info("b", 200, 50)}));
  EXPECT_EQ(v.wanted(), std::nullopt);
  EXPECT_EQ(v.next(), "a (1/2, 100x100, side by side)");
  EXPECT_EQ(v.wanted(), "a");
  EXPECT_EQ(v.current(), nullptr) << "not read back yet";
  v.setTile(tile("a", 100, 100));
  DebugPlacement p = v.place(640, 360, 640, 360);
  EXPECT_EQ(p.frame, (Rect{0, 90, 320, 180}));
  EXPECT_EQ(p.tile, (Rect{320 + 0, 20, 320, 320}));
  EXPECT_EQ(v.next(), "b (2/2, 200x50, side by side)");
  EXPECT_EQ(v.wanted(), "b");
  v.setTile(tile("b", 200, 50));
  EXPECT_EQ(v.toggleLayout(), "b (2/2, 200x50, full screen)");
  p = v.place(640, 360, 640, 360);
  EXPECT_EQ(p.frame.width, 0u);
  EXPECT_EQ(p.tile, (Rect{0, 100, 640, 160}));
  // The next frame has "b" still (elsewhere in its list): the selection stays.
  EXPECT_FALSE(v.setImages({info("c", 8, 8), info("b", 200, 50)}));
  EXPECT_EQ(v.status(), "b (2/2, 200x50, full screen)");
  // A frame without "b": the first image is wanted now, and the old tile is gone.
  const uint64_t revision = v.revision();
  EXPECT_TRUE(v.setImages({info("c", 8, 8)}));
  EXPECT_EQ(v.wanted(), "c");
  EXPECT_EQ(v.current(), nullptr);
  EXPECT_GT(v.revision(), revision);
  v.hide();
  EXPECT_EQ(v.wanted(), std::nullopt);
  v.setImages({});
  EXPECT_EQ(v.status(), "no debug resources");
}

TEST(SkyviewFileWatcher, SeesEditsAdditionsAndRemovals) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("skyview-watch-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "common");
  std::ofstream(dir / "a.comp") << "one";
  FileWatcher w(dir, std::chrono::milliseconds(0));
  EXPECT_FALSE(w.poll());
  std::ofstream(dir / "a.comp") << "two, longer";
  EXPECT_TRUE(w.poll());
  EXPECT_FALSE(w.poll());
  std::ofstream(dir / "common" / "b.glsl") << "new";
  EXPECT_TRUE(w.poll());
  fs::remove(dir / "common" / "b.glsl");
  EXPECT_TRUE(w.poll());
  fs::remove_all(dir);
}

TEST(SkyviewOptions, ParsesAndRejects) {
  ViewerOptions o =
      parseViewerOptions({"scene.yaml", "--set", "a.b=1", "--set=c=2", "--width", "160",
                          "--frames=3", "--report-fps", "--script", "wait 1; quit"});
  EXPECT_EQ(o.scenePath->string(), "scene.yaml");
  EXPECT_EQ(o.overrides, (std::vector<std::string>{"a.b=1", "c=2"}));
  EXPECT_EQ(o.width, 160);
  EXPECT_EQ(*o.frames, 3);
  EXPECT_TRUE(o.reportFps);
  EXPECT_FALSE(o.script.empty());
  EXPECT_THROW(parseViewerOptions({"--frames", "0"}), Error);
  EXPECT_THROW(parseViewerOptions({"--bogus"}), Error);
  EXPECT_THROW(parseViewerOptions({"a.yaml", "b.yaml"}), Error);
  EXPECT_THROW(parseViewerOptions({"--width"}), Error);
}

}  // namespace
}  // namespace sky::view
