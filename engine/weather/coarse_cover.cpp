#include "engine/weather/coarse_cover.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "engine/core/error.h"

namespace sky {
namespace {

// The map texels [first, last] a bilinear lookup can reach from any u in coarse texels
// [i - 1, i + 1] (of `coarse` across) of a map `size` texels across.
std::pair<uint32_t, uint32_t> reach(uint32_t i, uint32_t coarse, uint32_t size) {
  const double a = (double(i) - 1.0) / coarse * size, b = (double(i) + 2.0) / coarse * size;
  // A lookup at u reads texels floor(u size - 0.5) and the one after (clamped to the map).
  const double first = std::floor(a - 0.5), last = std::floor(b - 0.5) + 1.0;
  const double top = double(size - 1);
  return {uint32_t(std::clamp(first, 0.0, top)), uint32_t(std::clamp(last, 0.0, top))};
}

}  // namespace

glm::uvec2 coarseCoverSize(uint32_t width, uint32_t height) {
  return {(width + kWeatherCoarseBlock - 1) / kWeatherCoarseBlock,
          (height + kWeatherCoarseBlock - 1) / kWeatherCoarseBlock};
}

WeatherMap coarseCoverMap(const WeatherMap& map) {
  if (map.width == 0 || map.height == 0 || map.texels.size() != size_t(map.width) * map.height)
    internalError("coarseCoverMap: empty or inconsistent weather map");
  const glm::uvec2 size = coarseCoverSize(map.width, map.height);
  // Separable: the max over x ranges for every map row, then over y ranges.
  std::vector<glm::vec2> rows(size_t(size.x) * map.height, glm::vec2(0.0f));
  for (uint32_t i = 0; i < size.x; ++i) {
    const auto [x0, x1] = reach(i, size.x, map.width);
    for (uint32_t y = 0; y < map.height; ++y) {
      glm::vec2 m(0.0f);
      for (uint32_t x = x0; x <= x1; ++x) m = glm::max(m, glm::vec2(map.at(x, y)));
      rows[size_t(y) * size.x + i] = m;
    }
  }
  WeatherMap coarse;
  coarse.region = map.region;
  coarse.width = size.x;
  coarse.height = size.y;
  coarse.texels.resize(size_t(size.x) * size.y);
  for (uint32_t j = 0; j < size.y; ++j) {
    const auto [y0, y1] = reach(j, size.y, map.height);
    for (uint32_t i = 0; i < size.x; ++i) {
      glm::vec2 m(0.0f);
      for (uint32_t y = y0; y <= y1; ++y) m = glm::max(m, rows[size_t(y) * size.x + i]);
      coarse.texels[size_t(j) * size.x + i] = glm::vec4(m, std::max(m.x, m.y), 0.0f);
    }
  }
  return coarse;
}

}  // namespace sky
