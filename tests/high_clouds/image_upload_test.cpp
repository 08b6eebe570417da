// engine/gpu/image_upload: float texels reach the image in its own format, the image ends in
// the asked layout, and a frame graph importing it afterwards (and an upload after that
// graph) synchronise from the ResourceState the upload leaves, with validation on.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/gpu/image.h"
#include "engine/gpu/image_upload.h"
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
  desc.name = "upload test";
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

TEST_F(GpuTest, UploadedTexelsReadBackInEachFormat) {
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
    uploadImage(ctx(), image.image, image.state, pixels);
    EXPECT_EQ(image.state.layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    const std::vector<float> back = readBack(runtime, image);
    ASSERT_EQ(back.size(), pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i)
      ASSERT_NEAR(back[i], pixels[i], c.tolerance) << "value " << i;
  }
}

TEST_F(GpuTest, UploadAfterAGraphReplacesTheContents) {
  GraphRuntime runtime(ctx());
  PersistentImage image = makeImage(ctx(), VK_FORMAT_R16G16B16A16_SFLOAT, 8, 8);
  uploadImage(ctx(), image.image, image.state, std::vector<float>(8 * 8 * 4, 0.25f),
              VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(image.state.layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(readBack(runtime, image), std::vector<float>(8 * 8 * 4, 0.25f));
  // The graph left the image as a transfer source; the next upload starts from there.
  EXPECT_EQ(image.state.layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  uploadImage(ctx(), image.image, image.state, std::vector<float>(8 * 8 * 4, 0.75f));
  EXPECT_EQ(readBack(runtime, image), std::vector<float>(8 * 8 * 4, 0.75f));
}

TEST_F(GpuTest, UploadOfTheWrongSizeIsAnInternalError) {
  PersistentImage image = makeImage(ctx(), VK_FORMAT_R16G16B16A16_SFLOAT, 4, 4);
  try {
    uploadImage(ctx(), image.image, image.state, std::vector<float>(4 * 4 * 3, 0.0f));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Internal);
    EXPECT_NE(std::string(e.what()).find("48 values for 16 texels"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sky
