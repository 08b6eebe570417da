#pragma once
// Converts read-back texels of the engine's formats to 32-bit floats.
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

namespace sky {

// `bytes` holds width*height*depth tightly packed texels of `format`; returns
// channel-interleaved floats (formatChannelCount(format) per texel).
std::vector<float> texelsToFloat(VkFormat format, std::span<const uint8_t> bytes);
float halfToFloat(uint16_t h);

}  // namespace sky
