// skyrender against hostile input (issue 31): inputs that are not regular files, a scene
// too large to parse, an argument that would fail only after the render, and a signal while
// the device starts. The commands that could block run under `timeout`, so a regression fails
// instead of hanging the suite.
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_fixture.h"

namespace sky {
namespace {

// Issue 31, 5 and 7: a FIFO as an input blocked open() forever, and a scene that is a
// symlink to /dev/zero read until memory ran out. Each is refused before it is opened, with
// one line. `timeout` keeps a regression from hanging the suite (it exits 124).
TEST_F(SkyrenderCli, AFifoOrADeviceAsAnInputIsRefusedBeforeItIsOpened) {
  const fs::path fifo = mDir / "scene.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  CliRun r = run("render " + fifo.string() + " --out " + out(), "timeout 60");
  EXPECT_EQ(r.rc, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
  EXPECT_THAT(r.err, HasSubstr("scene.yaml: is a FIFO, not a regular file"));
  EXPECT_TRUE(outEmpty());
  const fs::path ocio = mDir / "config.ocio";
  ASSERT_EQ(::mkfifo(ocio.c_str(), 0600), 0);
  r = run("render --width 16 --height 9 --ocio " + ocio.string() + " --out " + out(),
          "timeout 60");
  EXPECT_EQ(r.rc, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("config.ocio: is a FIFO, not a regular file"));
  const fs::path exr = mDir / "top.exr";
  ASSERT_EQ(::mkfifo(exr.c_str(), 0600), 0);
  r = run("dsc " + exr.string(), "timeout 60");
  EXPECT_EQ(r.rc, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("top.exr: is a FIFO, not a regular file"));
  const fs::path zero = mDir / "zero.yaml";
  fs::create_symlink("/dev/zero", zero);
  r = run("validate " + zero.string(), "timeout 60");
  EXPECT_EQ(r.rc, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
  EXPECT_THAT(r.err, HasSubstr("zero.yaml: is a character device, not a regular file"));
}

TEST_F(SkyrenderCli, AHugeSceneFileIsRefusedBeforeItIsParsed) {
  // 17 MB of comments: over the 16 MB a scene file may have.
  const fs::path big = mDir / "big.yaml";
  {
    std::ofstream f(big);
    const std::string line(1023, '#');
    for (int i = 0; i < 17 * 1024; ++i) f << line << '\n';
  }
  CliRun r = run("validate " + big.string(), "timeout 60");
  EXPECT_EQ(r.rc, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
  EXPECT_THAT(r.err, HasSubstr("big.yaml: is 17825792 bytes, more than the 16777216 read from it"));
}

TEST_F(SkyrenderCli, DumpGraphIntoAFolderIsRefusedBeforeTheRender) {
  // Issue 31, 3: it used to fail with exit 2 after sky.exr, sky.png and sky.json were written.
  expectBadInput("--width 16 --height 9 --dump-graph " + mDir.string(),
                 {"--dump-graph", "is a directory"});
  expectBadInput("--width 16 --height 9 --dump-graph " + (mDir / "no" / "g.dot").string(),
                 {"--dump-graph", "does not exist"});
}

TEST_F(SkyrenderCli, ASignalWhileTheDeviceStartsLeavesNoFolderAndExits143) {
  // Issue 31, 8: SIGTERM 0.3 s in, while the device and pipelines are made, killed the process
  // without a word and left the empty --out folder. Now the run stops before its first frame.
  // A 97-frame time-lapse, so a fast device is still rendering when the signal comes: then
  // the frames before it are kept whole. Either way the run says how far it got.
  const fs::path dir = mDir / "early";
  CliRun r = run("render --width 16 --height 9 --time 2024-06-21T00:00Z/2024-06-22T00:00Z/15m "
                 "--out " + dir.string(),
                 "timeout --preserve-status -s TERM 0.3");
  EXPECT_EQ(r.rc, 143) << r.err;
  EXPECT_THAT(r.err, HasSubstr("interrupted after ")) << "the signal was caught, not fatal";
  EXPECT_THAT(r.err, HasSubstr(" of 97 frames (SIGTERM)"));
  if (r.err.find("interrupted after 0 of") != std::string::npos)
    EXPECT_FALSE(fs::exists(dir)) << "the folder the run made and wrote nothing into is removed";
  else
    EXPECT_TRUE(fs::exists(dir / "sky_0001.json")) << "the frames before the signal are whole";
}

}  // namespace
}  // namespace sky
