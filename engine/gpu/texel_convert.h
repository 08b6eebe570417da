#pragma once
// Converts texels of the engine's formats to and from 32-bit floats (read-backs, uploads).
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

namespace sky {

// `bytes` holds width*height*depth tightly packed texels of `format`; returns
// channel-interleaved floats (formatChannelCount(format) per texel).
std::vector<float> texelsToFloat(VkFormat format, std::span<const uint8_t> bytes);
float halfToFloat(uint16_t h);
// The reverse for uploads: channel-interleaved floats to tightly packed texels of `format`
// (rgba32f, r32f, rgba16f, r16f; r8 and rgba8 unorm clamp to 0..1, NaN to 0). Internal error
// for another format.
std::vector<uint8_t> floatsToTexels(VkFormat format, std::span<const float> pixels);

}  // namespace sky
