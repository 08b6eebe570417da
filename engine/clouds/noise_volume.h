#pragma once
// A CPU copy of one baked cloud-noise volume (passes/cloud_noise): what the coverage
// calibration reads without touching the GPU.
#include <cstdint>
#include <vector>

namespace sky {

// size^3 texels of interleaved RGBA8 (4 bytes a texel), x fastest, then y, then z; the bytes
// are the GPU texture's R8G8B8A8_UNORM texels exactly (value = byte / 255). Empty (size 0)
// before the first bake or cache load.
struct NoiseVolume {
  uint32_t size = 0;
  std::vector<uint8_t> rgba;
};

}  // namespace sky
