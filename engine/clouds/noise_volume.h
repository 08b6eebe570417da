#pragma once
// A CPU copy of one baked cloud-noise volume (passes/cloud_noise): what the coverage
// calibration reads without touching the GPU.
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

namespace sky {

// size^3 texels of interleaved RGBA8 (4 bytes a texel), x fastest, then y, then z; the bytes
// are the GPU texture's R8G8B8A8_UNORM texels exactly (value = byte / 255). Empty (size 0)
// before the first bake or cache load.
struct NoiseVolume {
  uint32_t size = 0;
  std::vector<uint8_t> rgba;
};

// The mean of each channel over the volume, in [0, 1] (0 when empty): what the channel's
// octaves average to where a sample is too wide to resolve them.
inline glm::vec4 channelMeans(const NoiseVolume& v) {
  double sum[4] = {0, 0, 0, 0};
  for (size_t i = 0; i + 3 < v.rgba.size(); i += 4)
    for (size_t c = 0; c < 4; ++c) sum[c] += v.rgba[i + c];
  const double texels = static_cast<double>(v.rgba.size() / 4);
  if (texels == 0) return glm::vec4(0.0f);
  return glm::vec4(glm::dvec4(sum[0], sum[1], sum[2], sum[3]) / (255.0 * texels));
}

}  // namespace sky
