#pragma once
// Reflection of compute-shader SPIR-V, read straight from the words (no SPIRV-Reflect or
// SPIRV-Cross dependency): what a pipeline layout needs to be built from the shader itself.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan_core.h>

namespace sky {

struct DescriptorBinding {
  uint32_t set = 0, binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  uint32_t count = 1;  // array length; 0 for a runtime-sized array (descriptor indexing)
  std::string name;    // the variable's name, or the block's type name for an anonymous block
  VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D;  // images only
  VkFormat storageFormat = VK_FORMAT_UNDEFINED;      // storage images/texel buffers only
};

struct ShaderReflection {
  std::array<uint32_t, 3> localSize{1, 1, 1};
  std::vector<DescriptorBinding> bindings;  // sorted by (set, binding)
  // Bytes up to the end of the last member, rounded up to 4 (Vulkan's rule); 0 if none.
  uint32_t pushConstantSize = 0;
};

// Reflects a SPIR-V module; pure function, safe from any thread. Malformed input (bad magic,
// truncated instruction, dangling id) is an Internal error naming the word offset.
ShaderReflection reflectSpirv(std::span<const uint32_t> words);

// Maps a SPIR-V image format (spv::ImageFormat value) to Vulkan; VK_FORMAT_UNDEFINED for
// Unknown or a format Vulkan lacks.
VkFormat vkFormatFromSpirv(uint32_t spirvImageFormat);

}  // namespace sky
