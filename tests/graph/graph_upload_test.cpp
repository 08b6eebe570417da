// FrameGraph::upload: float texels reach the image in its own format through a graph transfer
// pass; a later graph (and an upload after it) synchronise from the ResourceState the frame
// leaves, with validation on; the pass is kept though nothing in its frame reads the image;
// afterExecute runs only for a frame that ran.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/gpu/image.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "gpu_test.h"

namespace sky {
namespace {
using test::GpuTest;

std::vector<float> readBack(GraphRuntime& runtime, PersistentImage& image) {
  FrameGraph graph(runtime);
  graph.requestOutput(graph.importImage(image), "image");
  return graph.execute().output("image").pixels;
}

PersistentImage makeImage(const Context& ctx, VkFormat format, uint32_t w, uint32_t h) {
  ImageDesc desc;
  desc.name = "upload_test";
  desc.format = format;
  desc.width = w;
  desc.height = h;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
               VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  return {Image(ctx, desc), {}};
}

std::vector<float> ramp(size_t count, float scale, float offset) {
  std::vector<float> v(count);
  for (size_t i = 0; i < count; ++i) v[i] = offset + scale * float(i % 97) / 96.0f;
  return v;
}

TEST_F(GpuTest, UploadedTexelsReadBackInEachFormatInTheSameFrame) {
  GraphRuntime runtime(ctx());
  struct Case {
    VkFormat format;
    uint32_t channels;
    float scale, offset, tolerance;
  };
  const Case cases[] = {
      {VK_FORMAT_R16G16B16A16_SFLOAT, 4, 4.0f, -2.0f, 2.0f / 1024},  // half: 11 bits
      {VK_FORMAT_R16_SFLOAT, 1, 1.0f, 0.0f, 1.0f / 2048},
      {VK_FORMAT_R32G32B32A32_SFLOAT, 4, 100.0f, -50.0f, 0.0f},
      {VK_FORMAT_R8G8B8A8_UNORM, 4, 1.0f, 0.0f, 0.51f / 255}  // nearest code,
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(formatName(c.format));
    PersistentImage image = makeImage(ctx(), c.format, 13, 7);
    const std::vector<float> pixels = ramp(13 * 7 * c.channels, c.scale, c.offset);
    FrameGraph graph(runtime);
    const ImageId uploaded = graph.upload(graph.importImage(image), pixels, "upload");
    graph.requestOutput(uploaded, "image");
    const FrameResult r = graph.execute();
    ASSERT_EQ(r.passes.size(), 2u);
    EXPECT_EQ(r.passes[0].name, "upload");
    EXPECT_EQ(r.passes[1].name, "readback");
    const std::vector<float>& back = r.output("image").pixels;
    ASSERT_EQ(back.size(), pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i)
      ASSERT_NEAR(back[i], pixels[i], c.tolerance) << "value " << i;
  }
}

TEST_F(GpuTest, AnUploadNothingReadsIsKeptAndLaterFramesSeeIt) {
  GraphRuntime runtime(ctx());
  PersistentImage image = makeImage(ctx(), VK_FORMAT_R16G16B16A16_SFLOAT, 8, 8);
  bool landed = false;
  {
    FrameGraph graph(runtime);
    (void)graph.upload(graph.importImage(image), std::vector<float>(8 * 8 * 4, 0.25f), "upload");
    graph.afterExecute([&] { landed = true; });
    EXPECT_EQ(graph.execute().passes.size(), 1u) << "the upload was culled";
  }
  EXPECT_TRUE(landed);
  EXPECT_EQ(image.state.layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  EXPECT_EQ(readBack(runtime, image), std::vector<float>(8 * 8 * 4, 0.25f));
  // The read-back left the image as a transfer source; the next upload starts from there.
  EXPECT_EQ(image.state.layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  {
    FrameGraph graph(runtime);
    (void)graph.upload(graph.importImage(image), std::vector<float>(8 * 8 * 4, 0.75f), "upload");
    graph.execute();
  }
  EXPECT_EQ(readBack(runtime, image), std::vector<float>(8 * 8 * 4, 0.75f));
}

TEST_F(GpuTest, AFrameNeverExecutedCallsNothingAfterIt) {
  GraphRuntime runtime(ctx());
  PersistentImage image = makeImage(ctx(), VK_FORMAT_R16_SFLOAT, 4, 4);
  bool landed = false;
  {
    FrameGraph graph(runtime);
    (void)graph.upload(graph.importImage(image), std::vector<float>(16, 0.5f), "upload");
    graph.afterExecute([&] { landed = true; });
    // Dropped before execute(), as a frame whose building failed.
  }
  EXPECT_FALSE(landed);
}

TEST_F(GpuTest, UploadOfTheWrongSizeIsAnInternalError) {
  GraphRuntime runtime(ctx());
  PersistentImage image = makeImage(ctx(), VK_FORMAT_R16G16B16A16_SFLOAT, 4, 4);
  FrameGraph graph(runtime);
  try {
    (void)graph.upload(graph.importImage(image), std::vector<float>(4 * 4 * 3, 0.0f), "upload");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Internal);
    EXPECT_NE(std::string(e.what()).find("48 values for 16 texels"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sky
