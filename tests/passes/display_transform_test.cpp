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
#include "engine/core/error.h"
#include "engine/gpu/barriers.h"
#include "engine/core/paths.h"
#include "engine/gpu/buffer.h"
#include "engine/gpu/context.h"
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

// skyview's path (RenderOptions::displayTarget): the codes go into the caller's image, kept in
// its layout between frames, and nothing comes back to the host. They must be the codes the
// read-back gives, bit for bit.
TEST_F(DisplayTransformTest, WritesIntoTheCallersImageWithNothingReadBack) {
  ::unsetenv("OCIO");
  const OcioOutput ocio = OcioOutput::load();
  ShaderCompiler compiler;
  Renderer renderer(ctx(), compiler);
  const Scene scene = loadSceneFile(configDir() / "tests" / "clouds" / "cumulus_noon.yaml",
                                    {"output.width=96", "output.height=54"});
  RenderOptions options;
  options.gpuDisplay = &ocio;
  options.readBack = ReadBack::Display;
  const RenderedFrame readBack = renderer.render(scene, scene.time.start, options);
  ASSERT_EQ(readBack.display.size(), 96u * 54u * 4u);

  // The caller's image, in the layout it keeps it in (as skyview's window image).
  constexpr VkImageLayout kLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  auto makeTarget = [&](uint32_t width, uint32_t height) {
    ImageDesc desc;
    desc.name = "window_frame";
    desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.width = width;
    desc.height = height;
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    PersistentImage image{Image(ctx(), desc), {}};
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
      b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
      b.newLayout = kLayout;
      b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      b.image = image.image.image();
      b.subresourceRange = image.image.range();
      VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
      d.imageMemoryBarrierCount = 1;
      d.pImageMemoryBarriers = &b;
      vkCmdPipelineBarrier2(cmd, &d);
    });
    return image;
  };
  PersistentImage target = makeTarget(96, 54);
  options.displayTarget = &target;
  options.displayTargetLayout = kLayout;
  const RenderedFrame direct = renderer.render(scene, scene.time.start, options);
  EXPECT_TRUE(direct.display.empty()) << "the codes stay on the GPU";
  for (const ReadbackImage& o : direct.frame.outputs) ADD_FAILURE() << "read back: " << o.label;

  Buffer host(ctx(),
              {"codes", 96 * 54 * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, BufferMemory::HostVisible});
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {96, 54, 1};
    vkCmdCopyImageToBuffer(cmd, target.image.image(), kLayout, host.buffer(), 1, &region);
    copiesVisibleToHost(cmd);
  });
  const auto* codes = static_cast<const uint8_t*>(host.mapped());
  EXPECT_TRUE(std::equal(readBack.display.begin(), readBack.display.end(), codes))
      << "the codes in the caller's image differ from the read-back's";

  // An image of another size is the caller's mistake, said before anything runs.
  PersistentImage small = makeTarget(48, 27);
  options.displayTarget = &small;
  EXPECT_THROW(renderer.render(scene, scene.time.start, options), Error);
}

}  // namespace
}  // namespace sky
