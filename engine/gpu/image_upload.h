#pragma once
// Filling a device-local image from the host: float texels go through a host-visible staging
// buffer and one copy. For persistent images (loaded textures, cached bakes) that frame graphs
// import afterwards: the upload updates the image's ResourceState so the next graph's barriers
// start from where the upload left the image.
#include <span>

#include <vulkan/vulkan.h>

namespace sky {

class Context;
class Image;
struct ResourceState;  // engine/graph/graph_desc.h (plain data; no link dependency)

// Converts `pixels` (interleaved floats, formatChannelCount(format) per texel, row 0 = top,
// width * height * depth texels) to `image`'s format (rgba16f, rgba32f, r16f, r32f, r8,
// rgba8 unorm), copies them over the whole image and leaves it in `layout`
// (SHADER_READ_ONLY_OPTIMAL or GENERAL). `state` is where the image stood (its last write is
// waited for; the old contents are discarded) and becomes what a later frame graph must wait
// for. The image needs TRANSFER_DST usage. Blocks until the copy is done (Context::submitAndWait).
void uploadImage(const Context& ctx, const Image& image, ResourceState& state,
                 std::span<const float> pixels,
                 VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);

}  // namespace sky
