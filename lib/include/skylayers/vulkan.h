#pragma once
// skylayers on the host's own Vulkan device (docs/library.md, "On the host's device").
//
//   #include <skylayers/vulkan.h>     // includes <vulkan/vulkan.h>: link Vulkan::Vulkan too
//   skylayers::VulkanDevice host{instance, physicalDevice, device, queueFamily, 0};
//   skylayers::DeviceOptions options;
//   options.vulkan = &host;
//   skylayers::Sky sky = skylayers::Sky::fromFile("scene.yaml", {}, options);
//
// What the host provides: a Vulkan 1.3 instance and device, the device created with the
// synchronization2 and maintenance4 features enabled (the shaders' workgroup sizes are
// LocalSizeId, which needs maintenance4; validation says so otherwise), and a queue (family, index)
// that can run compute shaders. The Sky makes its images, buffers and pipelines on that device,
// records its own command buffers, submits them on that queue and waits for them; it never destroys
// the host's objects, which must outlive the Sky. The host must not submit on that queue from
// another thread while a Sky call runs. Validation is the host's: its instance's layers and
// messenger see the Sky's calls, and Sky::validationMessages() stays 0.
//
// Sky::record draws into the host's own images with its depth, in its command buffer
// (HostFrame below; docs/library.md, "Into the host's images", for the formats, layouts,
// depth conventions, synchronisation and what a host must not do).
#include <array>
#include <cstdint>
#include <limits>

#include <vulkan/vulkan.h>

#include <skylayers/skylayers.h>

namespace skylayers {

struct VulkanDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  uint32_t queueIndex = 0;
};

// One of the host's images, as Sky::record borrows it for a frame.
struct HostImage {
  VkImage image = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  // Where the image stands when the recorded commands start, and where they leave it.
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  uint32_t width = 0, height = 0;
};

// How the host's depth values map to distance. A perspective projection in Vulkan's clip
// space (depth 0..1), in metres: near and far planes (far may be infinite), standard (near at
// 0) or reverse-Z (near at 1). Or the host's projection matrix itself, which then wins.
struct DepthConvention {
  bool reverseZ = false;
  double nearM = 0.1;
  double farM = std::numeric_limits<double>::infinity();
  // Column-major, Vulkan clip space (depth 0..1, w = -z of the view: m[11] = -1, m[15] = 0);
  // m[10] and m[14] give a depth's distance. Its far end (depth 0 or 1, the larger distance)
  // is where the host drew nothing.
  bool useProjection = false;
  std::array<double, 16> projection{};
};

// A frame drawn into the host's images (Sky::record).
struct HostFrame {
  // The host's command buffer, recording, from a pool of the Sky's queue family.
  VkCommandBuffer commandBuffer = VK_NULL_HANDLE;
  // The host's scene-linear colour, VK_FORMAT_R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT,
  // made with VK_IMAGE_USAGE_STORAGE_BIT; 2D, one mip level, one layer, one sample. Its size
  // becomes the Sky's image size.
  HostImage colour;
  // Optional (image VK_NULL_HANDLE: the sky everywhere). The host's depth, the colour's
  // size: VK_FORMAT_D16_UNORM, X8_D24_UNORM_PACK32, D32_SFLOAT, D24_UNORM_S8_UINT or
  // D32_SFLOAT_S8_UINT, made with VK_IMAGE_USAGE_SAMPLED_BIT; read, never written.
  HostImage depth;
  DepthConvention depthConvention;
};

}  // namespace skylayers
