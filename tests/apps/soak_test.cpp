// A long time-lapse in one process keeps its memory flat (issue 13: a sequence grew about
// 2 MB a frame, 4 GB over 2,000 frames, until lavapipe's per-dispatch shader recompiles were
// removed, see GraphRuntime::uploadUniform). 2,000 frames of the default scene at 32x18,
// 33 h 19 min a minute apart; every report gives the process's resident memory, and from
// frame 200 on it must stay within 5 % of frame 200's. ctest label "soak"; CI runs it with
// the rest. 32x18, not 64x36: the frames run every pass either way, and a night frame at
// 64x36 took 0.5 s (the march, and the cloud shadow map made again as the light moves), so
// 2,000 of them were 13 minutes of CI (issue 30's stills made the march 1.2x dearer).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "tests/apps/cli_fixture.h"

namespace sky {
namespace {

TEST_F(SkyrenderCli, TwoThousandFramesInOneProcessKeepMemoryFlat) {
  // The core validation checks alone: synchronisation validation (on in every other test)
  // keeps an access history per resource, which is neither what this test measures nor
  // cheap over 2,000 frames; the same passes' barriers are checked by the other tests.
  CliRun r =
      run("render --width 32 --height 18 --time "
          "2024-06-21T00:00+02:00/2024-06-22T09:19+02:00/1m --out " +
              out(),
          "SKY_VALIDATION=core");
  ASSERT_EQ(r.rc, 0) << r.err;
  auto residentMib = [&](int frame) {
    char name[32];
    std::snprintf(name, sizeof name, "sky_%04d.json", frame);
    const nlohmann::json report = nlohmann::json::parse(readTextFile(mDir / "out" / name));
    return report.value("process", nlohmann::json::object()).value("resident_mib", std::nan(""));
  };
  ASSERT_TRUE(fs::exists(mDir / "out" / "sky_2000.json")) << r.out;
  const double atFrame200 = residentMib(200);
  ASSERT_TRUE(std::isfinite(atFrame200)) << "the reports give no process.resident_mib";
  double most = atFrame200;
  int worst = 200;
  for (int frame = 300; frame <= 2000; frame += 100)
    if (const double mib = residentMib(frame); mib > most) {
      most = mib;
      worst = frame;
    }
  std::printf(
      "[ soak ] resident %.1f MiB at frame 10, %.1f at 200, %.1f at 2000, most %.1f (frame %d)\n",
      residentMib(10), atFrame200, residentMib(2000), most, worst);
  EXPECT_LE(most, 1.05 * atFrame200) << "resident memory grew from frame 200 to frame " << worst;
}

}  // namespace
}  // namespace sky
