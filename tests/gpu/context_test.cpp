// engine/gpu: device choice, validation plumbing, resources, timestamps, texel conversion.
#include <algorithm>
#include <cstdlib>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/gpu/buffer.h"
#include "engine/gpu/image.h"
#include "engine/gpu/texel_convert.h"
#include "engine/gpu/timestamp_pool.h"
#include "gpu_test.h"

namespace sky {
namespace {

using ::testing::HasSubstr;

TEST(GpuValidation, TestsRunWithTheLayersOn) {
  const char* env = std::getenv("SKY_VALIDATION");
  ASSERT_TRUE(env && std::string(env) == "1") << "tests/support sets SKY_VALIDATION=1";
  EXPECT_TRUE(test::sharedContext().validationEnabled());
}

TEST(GpuValidation, AMisuseReachesTheHandler) {
  // A private context with its own handler: this test wants the message, the shared one fails on
  // it.
  ContextOptions options;
  options.validation = true;
  std::vector<std::string> messages;
  options.onValidationMessage = [&](std::string_view m) { messages.emplace_back(m); };
  Context ctx(options);
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 0;  // VUID-VkBufferCreateInfo-size-00912
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  if (vkCreateBuffer(ctx.device(), &info, nullptr, &buffer) == VK_SUCCESS && buffer)
    vkDestroyBuffer(ctx.device(), buffer, nullptr);
  ASSERT_FALSE(messages.empty());
  EXPECT_THAT(messages.front(), HasSubstr("size"));
  EXPECT_EQ(ctx.validationMessageCount(), messages.size());
}

// Synchronisation validation is on with the layers (issue 31): two writes to one buffer
// with no barrier between them are a hazard, and it reaches the handler like any message.
TEST(GpuValidation, AHazardBetweenTwoWritesReachesTheHandler) {
  ContextOptions options;
  options.validation = true;
  std::vector<std::string> messages;
  options.onValidationMessage = [&](std::string_view m) { messages.emplace_back(m); };
  Context ctx(options);
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 256;
  info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateBuffer(ctx.device(), &info, nullptr, &buffer), VK_SUCCESS);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device(), buffer, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = ctx.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VkDeviceMemory memory = ctx.allocate(alloc, "the hazard test's buffer");
  ASSERT_EQ(vkBindBufferMemory(ctx.device(), buffer, memory, 0), VK_SUCCESS);
  ASSERT_TRUE(messages.empty()) << messages.front();
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, buffer, 0, 256, 1u);
    vkCmdFillBuffer(cmd, buffer, 0, 256, 2u);  // no barrier: write after write
  });
  vkDestroyBuffer(ctx.device(), buffer, nullptr);
  vkFreeMemory(ctx.device(), memory, nullptr);
  ASSERT_FALSE(messages.empty()) << "synchronisation validation is off";
  EXPECT_THAT(messages.front(), HasSubstr("WRITE_AFTER_WRITE"));
}

TEST(GpuContext, GpuByIndexAndUnknownNameListsDevices) {
  ContextOptions byIndex;
  byIndex.gpu = "0";
  Context first(byIndex);
  EXPECT_FALSE(first.deviceName().empty());

  ContextOptions byName;
  byName.gpu = "no-such-gpu-xyz";
  try {
    Context c(byName);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_THAT(e.what(),
                HasSubstr("--gpu no-such-gpu-xyz: no such Vulkan device (available: 0: "));
  }
  ContextOptions byBadIndex;
  byBadIndex.gpu = "99";
  EXPECT_THROW(Context c(byBadIndex), Error);
}

class GpuResources : public test::GpuTest {};

// lavapipe gets the define that hides parameter values from its per-dispatch inlining
// (shaders/common/params_block.glsl); other drivers get none, so their shaders read plain
// uniform blocks.
TEST_F(GpuResources, OnlyLavapipeGetsTheParamsIndexWorkaround) {
  const auto& defines = ctx().shaderDefines();
  const bool has = std::any_of(defines.begin(), defines.end(), [](const auto& d) {
    return d.first == "SKY_UNFOLDABLE_PARAMS_INDEX" && d.second == "1";
  });
  EXPECT_EQ(has, ctx().driverId() == VK_DRIVER_ID_MESA_LLVMPIPE) << ctx().deviceName();
}

TEST_F(GpuResources, ImagesBuffersAndImpossibleSizes) {
  ImageDesc d3;
  d3.name = "volume";
  d3.dim = ImageDim::Tex3D;
  d3.format = VK_FORMAT_R8G8B8A8_UNORM;
  d3.width = d3.height = d3.depth = 32;
  d3.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  Image volume(ctx(), d3);
  EXPECT_TRUE(volume);
  EXPECT_NE(volume.view(), VK_NULL_HANDLE);
  Image moved = std::move(volume);
  EXPECT_FALSE(volume);
  EXPECT_TRUE(moved);

  ImageDesc huge;
  huge.name = "beauty";
  huge.width = 1u << 20;
  huge.height = 4;
  huge.usage = VK_IMAGE_USAGE_STORAGE_BIT;
  try {
    Image img(ctx(), huge);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_THAT(e.what(), HasSubstr("image 'beauty': 1048576x4x1 is not possible"));
  }

  Buffer host(ctx(), {"host", 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT, BufferMemory::HostVisible});
  ASSERT_NE(host.mapped(), nullptr);
  Buffer device(ctx(), {"device", 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, BufferMemory::Device});
  EXPECT_EQ(device.mapped(), nullptr);
}

TEST_F(GpuResources, TimestampsMeasureRecordedWork) {
  if (!ctx().hasTimestamps()) GTEST_SKIP() << "queue has no timestamps";
  TimestampPool pool(ctx(), 2);
  Buffer buf(ctx(), {"fill", 1 << 20, VK_BUFFER_USAGE_TRANSFER_DST_BIT, BufferMemory::Device});
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    pool.reset(cmd);
    pool.begin(cmd, 0);
    vkCmdFillBuffer(cmd, buf.buffer(), 0, VK_WHOLE_SIZE, 0x3f800000u);
    pool.end(cmd, 0);
    pool.begin(cmd, 1);
    pool.end(cmd, 1);
  });
  std::vector<double> ms = pool.resultsMs();
  ASSERT_EQ(ms.size(), 2u);
  EXPECT_GE(ms[0], 0.0);
  EXPECT_GE(ms[1], 0.0);
}

TEST(GpuTexels, HalfAndUnormConvertToFloat) {
  const uint16_t halves[] = {0x3c00, 0xc000, 0x3800, 0x7bff};  // 1, -2, 0.5, 65504
  std::vector<float> f = texelsToFloat(VK_FORMAT_R16_SFLOAT,
                                       {reinterpret_cast<const uint8_t*>(halves), sizeof halves});
  EXPECT_EQ(f, (std::vector<float>{1.0f, -2.0f, 0.5f, 65504.0f}));
  const uint8_t bytes[] = {0, 255, 51, 128};
  f = texelsToFloat(VK_FORMAT_R8G8B8A8_UNORM, bytes);
  EXPECT_FLOAT_EQ(f[1], 1.0f);
  EXPECT_FLOAT_EQ(f[2], 0.2f);
  EXPECT_THROW(texelsToFloat(VK_FORMAT_D32_SFLOAT, bytes), Error);
}

}  // namespace
}  // namespace sky
