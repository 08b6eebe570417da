// `skyrender dsc` as a user runs it (the fixture of tests/apps): the figures on stdout for a
// small EXR written here, the options, and one-line errors with exit code 2.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/files.h"
#include "engine/io/exr.h"
#include "tests/apps/cli_fixture.h"

namespace sky {
namespace {

// The CLI fixture of tests/apps (a private folder, exit code and both streams).
class DscCli : public SkyrenderCli {
protected:
  void expectBadInput(const std::string& args, const std::string& fragment) {
    const CliRun r = run(args);
    EXPECT_EQ(r.rc, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_THAT(r.err, HasSubstr("error: "));
    EXPECT_THAT(r.err, HasSubstr(fragment));
    EXPECT_EQ(r.out, "");
  }

  // A 16 x 8 top-down render: clouds (opacity 1) over the west half, map cover over the
  // west three quarters split between the layers.
  fs::path writeRender() const {
    LayeredImage exr;
    exr.width = 16;
    exr.height = 8;
    std::vector<float> clouds(16 * 8 * 4, 0.0f), weather(16 * 8 * 2, 0.0f);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 16; ++x) {
        const size_t i = size_t(y * 16 + x);
        clouds[i * 4 + 3] = x < 8 ? 1.0f : 0.0f;
        weather[i * 2] = x < 8 ? 1.0f : 0.0f;       // cover_low
        weather[i * 2 + 1] = x < 12 ? 1.0f : 0.0f;  // cover_mid
      }
    exr.layers.push_back({"clouds", {"R", "G", "B", "A"}, clouds});
    exr.layers.push_back({"weather", {"cover_low", "cover_mid"}, weather});
    writeExr(mDir / "render.exr", exr);
    return mDir / "render.exr";
  }

};

TEST_F(DscCli, PrintsTheFiguresOneLineEach) {
  const fs::path render = writeRender();
  // Cell 4: 4 x 2 blocks; rendered cloudy in columns 0-1, map in columns 0-2:
  // Dice 2 * 4 / (4 + 6) = 0.8, MAE 2 / 8, r = 0.577 (binary blocks, 4 of 8 vs 6 of 8).
  CliRun r = run("dsc " + render.string() + " --cell 4 --threshold 0.5");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, "dsc 0.800\nmae 0.250\ncorrelation 0.577\nblocks 8\n");
  EXPECT_EQ(r.err, "");
  // Defaults (cell 8, threshold 0.1): 2 x 1 blocks, too few for a correlation.
  r = run("dsc " + render.string());
  EXPECT_EQ(r.rc, 2);
  EXPECT_THAT(r.err, HasSubstr("holds 2 x 1 blocks; the comparison needs at least 2 x 2 (use "
                               "--cell 4 or less)"));
  // --cell=N form and the help text lists the command.
  r = run("dsc " + render.string() + " --cell=1");
  EXPECT_THAT(r.out, HasSubstr("blocks 128\n"));
  r = run("dsc --help");
  EXPECT_THAT(r.out, HasSubstr("skyrender dsc RENDER.exr"));
}

TEST_F(DscCli, BadArgumentsAndFilesExitTwoWithOneLine) {
  const fs::path render = writeRender();
  expectBadInput("dsc", "dsc needs one render EXR");
  expectBadInput("dsc " + render.string() + " " + render.string(), "one render");
  expectBadInput("dsc " + render.string() + " --cell 0", "--cell 0");
  expectBadInput("dsc " + render.string() + " --cell 2.5", "--cell '2.5'");
  expectBadInput("dsc " + render.string() + " --threshold 1", "--threshold 1");
  expectBadInput("dsc " + render.string() + " --threshold x", "--threshold 'x'");
  expectBadInput("dsc " + render.string() + " --bogus 1", "--bogus");
  expectBadInput("dsc " + (mDir / "none.exr").string(), "none.exr");

  LayeredImage plain;
  plain.width = plain.height = 2;
  plain.layers.push_back({"", {"R", "G", "B", "A"}, std::vector<float>(16, 0.5f)});
  writeExr(mDir / "plain.exr", plain);
  expectBadInput("dsc " + (mDir / "plain.exr").string(),
                 "plain.exr: no layer clouds.A (render with camera.mode geographic_topdown)");
}

}  // namespace
}  // namespace sky
