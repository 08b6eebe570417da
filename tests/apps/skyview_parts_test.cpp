// skyview's parts that need no window: the script, the debug view's layout, file polling and
// the command line.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "debug_view.h"
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

TEST(SkyviewDebugView, PlacesFrameAndTile) {
  DebugView v;
  EXPECT_EQ(v.next(), "no debug resources");
  EXPECT_EQ(v.layout(), DebugLayout::Hidden);
  // Hidden: the frame fills the window.
  EXPECT_EQ(v.place(640, 360, 320, 180).frame, (Rect{0, 0, 640, 360}));
  v.setImages({{"a", 100, 100, std::vector<uint8_t>(100 * 100 * 4)},
               {"b", 200, 50, std::vector<uint8_t>(200 * 50 * 4)}});
  EXPECT_EQ(v.next(), "a (1/2, 100x100, side by side)");
  DebugPlacement p = v.place(640, 360, 640, 360);
  EXPECT_EQ(p.frame, (Rect{0, 90, 320, 180}));
  EXPECT_EQ(p.tile, (Rect{320 + 0, 20, 320, 320}));
  EXPECT_EQ(v.next(), "b (2/2, 200x50, side by side)");
  EXPECT_EQ(v.toggleLayout(), "b (2/2, 200x50, full screen)");
  p = v.place(640, 360, 640, 360);
  EXPECT_EQ(p.frame.width, 0u);
  EXPECT_EQ(p.tile, (Rect{0, 100, 640, 160}));
  const uint64_t revision = v.revision();
  v.hide();
  EXPECT_EQ(v.current(), nullptr);
  v.setImages({});
  EXPECT_GT(v.revision(), revision);
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
