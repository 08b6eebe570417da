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
#include <cstdint>

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

}  // namespace skylayers
