#pragma once
// The weather map's coarse, conservative "max cover" map, with which the volumetric clouds
// skip empty space (engine/render/weather_textures.h puts both maps on the GPU).
#include <cstdint>

#include <glm/vec2.hpp>

#include "engine/weather/weather_map.h"

namespace sky {

// Map texels per coarse texel along each axis.
constexpr uint32_t kWeatherCoarseBlock = 8;

// ceil(size / kWeatherCoarseBlock) per axis.
glm::uvec2 coarseCoverSize(uint32_t width, uint32_t height);

// The coarse map of `map` (same region, coarseCoverSize texels): texel (i, j) holds in R the
// largest low cover, in G the largest mid cover and in B the larger of the two (A = 0) over
// every map texel a bilinear lookup can reach from anywhere within one coarse texel of
// (i, j)'s box (its 8x8 block dilated by one coarse texel, plus the lookup's one-texel
// footprint). So 0 at a coarse texel sampled at uv (nearest or linear) means no cloud
// within a coarse texel of uv, and a ray may skip that far.
WeatherMap coarseCoverMap(const WeatherMap& map);

}  // namespace sky
