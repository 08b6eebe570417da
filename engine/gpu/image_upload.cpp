#include "engine/gpu/image_upload.h"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "engine/core/error.h"
#include "engine/gpu/buffer.h"
#include "engine/gpu/context.h"
#include "engine/gpu/image.h"
#include "engine/graph/graph_desc.h"

namespace sky {
namespace {

std::vector<uint8_t> floatsToTexels(VkFormat format, std::span<const float> pixels) {
  std::vector<uint8_t> out;
  switch (format) {
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      out.resize(pixels.size() * 4);
      std::memcpy(out.data(), pixels.data(), out.size());
      break;
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      out.resize(pixels.size() * 2);
      for (size_t i = 0; i < pixels.size(); ++i) {
        const uint16_t h = glm::packHalf1x16(pixels[i]);
        std::memcpy(out.data() + i * 2, &h, 2);
      }
      break;
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8G8B8A8_UNORM:
      out.resize(pixels.size());
      for (size_t i = 0; i < pixels.size(); ++i) {
        const float v = std::isnan(pixels[i]) ? 0.0f : std::fmin(std::fmax(pixels[i], 0.0f), 1.0f);
        out[i] = static_cast<uint8_t>(std::lround(v * 255.0f));
      }
      break;
    default:
      internalError(std::string("upload of format ") + formatName(format) + " is not supported");
  }
  return out;
}

}  // namespace

void uploadImage(const Context& ctx, const Image& image, ResourceState& state,
                 std::span<const float> pixels, VkImageLayout layout) {
  const ImageDesc& d = image.desc();
  const uint32_t depth = d.dim == ImageDim::Tex3D ? d.depth : 1;
  const size_t texels = size_t(d.width) * d.height * depth;
  if (pixels.size() != texels * formatChannelCount(d.format))
    internalError("upload to image '" + d.name + "': " + std::to_string(pixels.size()) +
                  " values for " + std::to_string(texels) + " texels of " + formatName(d.format));
  if (!(d.usage & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
    internalError("upload to image '" + d.name + "': created without TRANSFER_DST usage");
  if (layout != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL && layout != VK_IMAGE_LAYOUT_GENERAL)
    internalError("upload to image '" + d.name + "': final layout must be shader-read or general");

  const std::vector<uint8_t> bytes = floatsToTexels(d.format, pixels);
  Buffer staging(ctx, {"upload " + d.name, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                       BufferMemory::HostVisible});
  // Host-coherent memory: the writes are visible to the device at submit without a flush.
  std::memcpy(staging.mapped(), bytes.data(), bytes.size());

  // Whatever wrote the image last (a frame graph pass) must finish before the copy overwrites
  // it; the contents are discarded (old layout UNDEFINED), the copy replaces all of them.
  // After the copy the data is made available and visible to every later stage at once, so
  // the state handed to the next graph only asks for an execution dependency on this barrier's
  // second scope (ALL_COMMANDS), which also orders the layout transition before its accesses.
  const VkPipelineStageFlags2 waitStage =
      state.writeStage != VK_PIPELINE_STAGE_2_NONE || state.layout != VK_IMAGE_LAYOUT_UNDEFINED
          ? VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT
          : VK_PIPELINE_STAGE_2_NONE;
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    VkImageMemoryBarrier2 toDst{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    toDst.srcStageMask = waitStage;
    toDst.srcAccessMask = waitStage ? state.writeAccess : VK_ACCESS_2_NONE;
    toDst.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    toDst.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    toDst.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    toDst.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    toDst.srcQueueFamilyIndex = toDst.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toDst.image = image.image();
    toDst.subresourceRange = image.range();
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &toDst;
    vkCmdPipelineBarrier2(cmd, &dep);

    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {d.width, d.height, depth};
    vkCmdCopyBufferToImage(cmd, staging.buffer(), image.image(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);

    VkImageMemoryBarrier2 toUse = toDst;
    toUse.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    toUse.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    toUse.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    toUse.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    toUse.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    toUse.newLayout = layout;
    dep.pImageMemoryBarriers = &toUse;
    vkCmdPipelineBarrier2(cmd, &dep);
  });
  state.layout = layout;
  state.writeStage = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  state.writeAccess = VK_ACCESS_2_NONE;
}

}  // namespace sky
