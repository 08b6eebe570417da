#pragma once
// Small tileable noise volumes built on the CPU for the calibration tests, with the channel
// layout of the real bake (shaders/common/cloud_noise_shared.h): shape R a low-frequency
// value-noise/Worley blend (a stand-in for Perlin-Worley), G, B, A inverted Worley of rising
// frequency; detail R, G, B inverted Worley of rising frequency, A their Lu (14) fbm.
// Independent of the bake so that the calibration is tested on noise it has never seen.
#include <cstdint>

#include "engine/clouds/noise_volume.h"

namespace sky::test {

NoiseVolume syntheticShapeVolume(uint32_t size, uint32_t seed);
NoiseVolume syntheticDetailVolume(uint32_t size, uint32_t seed);

}  // namespace sky::test
