// The GPU display path (passes/display_transform) against the exact CPU one (night look,
// exposure and OpenColorIO, engine/render/render_files.h displayPixels): the baked 3D table
// over a log2 shaper must show the same picture, by day, at sunset and by moonlight (where the
// night look and the exposure's lift both act), in both views that tone-map.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/color/ocio_output.h"
#include "engine/core/paths.h"
#include "engine/io/image_metrics.h"
#include "engine/render/exposure.h"
#include "engine/render/render_files.h"
#include "engine/render/renderer.h"
#include "engine/scene/scene_io.h"
#include "engine/shader/shader_compiler.h"
#include "gpu_test.h"

namespace sky {
namespace {

class DisplayTransformTest : public test::GpuTest {};

TEST_F(DisplayTransformTest, MatchesTheCpuPath) {
  ::unsetenv("OCIO");
  const OcioOutput ocio = OcioOutput::load();
  ShaderCompiler compiler;
  Renderer renderer(ctx(), compiler);
  struct Case {
    const char* scene;
    std::vector<std::string> set;
  };
  const Case cases[] = {
      {"clouds/cumulus_noon.yaml", {}},
      {"clouds/stratocumulus_dusk.yaml", {}},
      {"clouds/altocumulus_full_moon.yaml", {}},
      {"clouds/cumulus_noon.yaml", {"output.view=Un-tone-mapped", "output.exposure_ev=-1"}},
      {"night_full_moon.yaml", {"output.night_look=false"}},
  };
  for (const Case& c : cases) {
    std::vector<std::string> set = {"output.width=96", "output.height=54"};
    set.insert(set.end(), c.set.begin(), c.set.end());
    const Scene scene = loadSceneFile(configDir() / "tests" / c.scene, set);
    RenderOptions options;
    options.gpuDisplay = &ocio;
    options.readBack = ReadBack::Beauty;
    const RenderedFrame frame = renderer.render(scene, scene.time.start, options);
    ExposureMeter meter;
    const FrameExposure exposure = meter.expose(scene, frame, scene.time.start);
    EXPECT_DOUBLE_EQ(frame.displayEv, exposure.ev) << c.scene;
    std::vector<float> cpu = displayPixels(frame, scene, exposure, ocio);
    std::vector<float> gpu(frame.display.size());
    for (size_t i = 0; i < gpu.size(); ++i) gpu[i] = frame.display[i] / 255.0f;
    // RGB of both, the CPU's rounded to codes as the PNG would.
    std::vector<float> a, b;
    for (size_t i = 0; i < gpu.size(); ++i)
      if (i % 4 != 3) {
        a.push_back(gpu[i]);
        b.push_back(std::round(std::clamp(cpu[i], 0.0f, 1.0f) * 255.0f) / 255.0f);
      }
    const double db = psnr(a, b, 1.0), worst = maxAbsError(a, b) * 255.0;
    std::printf("%s %s: %.1f dB, at most %.0f codes apart\n", c.scene,
                c.set.empty() ? "" : c.set[0].c_str(), db, worst);
    EXPECT_GE(db, 45.0) << c.scene;
    EXPECT_LE(worst, 4.0) << c.scene;
  }
}

}  // namespace
}  // namespace sky
