#include "engine/render/weather_textures.h"

#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/weather/coarse_cover.h"

namespace sky {
namespace {

ImageDesc imageDesc(const char* name, const char* about, VkFormat format, DebugView view) {
  ImageDesc desc;
  desc.name = name;
  desc.about = about;
  desc.format = format;
  desc.view = view;
  return desc;
}

std::vector<float> floats(const std::vector<glm::vec4>& texels) {
  return {&texels.front().x, &texels.front().x + texels.size() * 4};
}

}  // namespace

WeatherTextures::WeatherTextures(const Context& ctx)
    : mSampler(ctx, SamplerWrap::Clamp, true),
      mMap(ctx, imageDesc("weather_map",
                          "the weather map over its region: R low cover, G mid cover, B cloud "
                          "type, A density",
                          VK_FORMAT_R16G16B16A16_SFLOAT, DebugView::Color)),
      mCoarse(ctx, imageDesc("weather_coarse",
                             "the weather map's maximum cover over coarse cells (empty-space "
                             "skip)",
                             VK_FORMAT_R16G16B16A16_SFLOAT, DebugView::Color)),
      mHighCover(ctx, imageDesc("high_cloud_regional_cover",
                                "the weather map's high cover, 0..1, over its region",
                                VK_FORMAT_R16_SFLOAT, DebugView::Scalar)) {}

WeatherTextures::Clouds WeatherTextures::addClouds(FrameGraph& graph, const WeatherMap& map,
                                                   uint64_t revision) {
  if (map.width == 0 || map.height == 0 || map.texels.size() != size_t(map.width) * map.height)
    internalError("weather textures: empty or inconsistent weather map");
  const glm::uvec2 coarse = coarseCoverSize(map.width, map.height);
  Clouds out;
  out.map = mMap.addTo(graph, revision, map.width, map.height, [&] { return floats(map.texels); });
  out.coarse = mCoarse.addTo(graph, revision, coarse.x, coarse.y,
                             [&] { return floats(coarseCoverMap(map).texels); });
  return out;
}

ImageId WeatherTextures::addHighCover(FrameGraph& graph, const WeatherMap& map,
                                      uint64_t revision) {
  if (map.width == 0 || map.height == 0 || map.coverHigh.size() != size_t(map.width) * map.height)
    internalError("regional high-cloud cover: the weather map has no high layer (" +
                  std::to_string(map.coverHigh.size()) + " values for " +
                  std::to_string(map.width) + "x" + std::to_string(map.height) + " texels)");
  return mHighCover.addTo(graph, revision, map.width, map.height,
                          [&] { return map.coverHigh; });
}

}  // namespace sky
