#include "engine/render/frame_layers.h"

#include <algorithm>
#include <limits>

#include <glm/glm.hpp>

#include "engine/core/error.h"

#include "engine/gpu/image.h"

namespace sky {

ImageLayer imageLayer(const ReadbackImage& img, std::string name, std::vector<std::string> channels,
                      bool fullFloat) {
  ImageLayer layer{std::move(name), std::move(channels), {}, fullFloat};
  const size_t w = img.width, h = img.height, d = img.depth, c = layer.channels.size();
  layer.pixels.resize(w * h * d * c);
  for (size_t z = 0; z < d; ++z)
    for (size_t y = 0; y < h; ++y)
      for (size_t x = 0; x < w; ++x) {
        const size_t src = ((z * h + y) * w + x) * img.channels;
        const size_t dst = (y * w * d + z * w + x) * c;
        for (size_t k = 0; k < c; ++k) layer.pixels[dst + k] = img.pixels[src + k];
      }
  return layer;
}

std::vector<std::string> channelNames(const ImageDesc& desc) {
  const size_t count = formatChannelCount(desc.format);
  std::vector<std::string> names;
  size_t start = 0;
  while (!desc.channels.empty() && start <= desc.channels.size() && names.size() < count) {
    const size_t comma = desc.channels.find(',', start);
    names.push_back(desc.channels.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (!names.empty()) return names;  // a pass that names fewer channels means only those
  static const char* const kRgba[] = {"R", "G", "B", "A"};
  for (size_t k = 0; k < count && k < 4; ++k) names.push_back(kRgba[k]);
  return names;
}

std::string frameLayerName(const ImageLayer& layer) {
  if (!layer.name.empty()) return layer.name;
  return layer.integer ? "label" : "beauty";
}

ImageLayer beautyLayer(const ReadbackImage& beauty) {
  return imageLayer(beauty, "", {"R", "G", "B", "A"}, true);
}

void appendAovLayers(LayeredImage& image, const ReadbackImage& sky, const ReadbackImage& highClouds,
                     const ReadbackImage* clouds, const ReadbackImage* depth) {
  image.layers.push_back(imageLayer(sky, "sky", {"R", "G", "B"}, true));
  image.layers.push_back(imageLayer(highClouds, "high_clouds", {"R", "G", "B", "A"}, true));
  // FLOAT: the depth of horizon clouds (up to ~200 km) is past half's 65504, and moonlit
  // clouds' radiance (1e-7) below its normal range.
  ImageLayer layer{"clouds", {"R", "G", "B", "A", "depth"}, {}, true};
  const size_t n = size_t(image.width) * size_t(image.height);
  layer.pixels.assign(n * 5, 0.0f);
  if (clouds && depth)
    for (size_t i = 0; i < n; ++i) {
      for (size_t k = 0; k < 4; ++k)
        layer.pixels[i * 5 + k] = clouds->pixels[i * clouds->channels + k];
      layer.pixels[i * 5 + 4] = depth->pixels[i * depth->channels];
    }
  image.layers.push_back(std::move(layer));
}

void appendPerceptionLayers(LayeredImage& image, const ReadbackImage& perception,
                            const ReadbackImage* cloudHit) {
  const size_t n = size_t(image.width) * size_t(image.height);
  ImageLayer* clouds = nullptr;
  for (ImageLayer& layer : image.layers)
    if (layer.name == "clouds") clouds = &layer;
  if (!clouds) internalError("appendPerceptionLayers: no clouds layer to extend");
  const size_t c0 = clouds->channels.size(), c1 = c0 + 2;
  std::vector<float> pixels(n * c1);
  for (size_t i = 0; i < n; ++i) {
    std::copy_n(clouds->pixels.begin() + i * c0, c0, pixels.begin() + i * c1);
    pixels[i * c1 + c0] = cloudHit ? cloudHit->pixels[i * cloudHit->channels] : 0.0f;
    pixels[i * c1 + c0 + 1] = cloudHit ? cloudHit->pixels[i * cloudHit->channels + 1]
                                       : std::numeric_limits<float>::infinity();
  }
  clouds->channels.push_back("optical_depth");
  clouds->channels.push_back("distance");
  clouds->pixels = std::move(pixels);

  ImageLayer label{"", {"label", "cloud_type"}, {}, false, true};
  ImageLayer air{"air", {"transmittance"}, {}, true};
  ImageLayer ground{"ground", {"cloud_shadow"}, {}, true};
  label.pixels.resize(n * 2);
  air.pixels.resize(n);
  ground.pixels.resize(n);
  const size_t pc = perception.channels;
  for (size_t i = 0; i < n; ++i) {
    label.pixels[i * 2] = perception.pixels[i * pc];
    label.pixels[i * 2 + 1] = perception.pixels[i * pc + 1];
    air.pixels[i] = perception.pixels[i * pc + 2];
    ground.pixels[i] = perception.pixels[i * pc + 3];
  }
  image.layers.push_back(std::move(label));
  image.layers.push_back(std::move(air));
  image.layers.push_back(std::move(ground));
}

ImageLayer weatherCoverLayer(const WeatherMap& map, const WeatherRegion& region, uint32_t width,
                             uint32_t height) {
  ImageLayer layer{"weather", {"cover_low", "cover_mid"}, {}};
  layer.pixels.resize(size_t(width) * height * 2);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const double lat = region.lat[1] + (region.lat[0] - region.lat[1]) * (y + 0.5) / height;
      const double lon = region.lon[0] + (region.lon[1] - region.lon[0]) * (x + 0.5) / width;
      const glm::vec4 w = map.sample(lat, lon);
      const size_t i = (size_t(y) * width + x) * 2;
      layer.pixels[i] = w.r;
      layer.pixels[i + 1] = w.g;
    }
  return layer;
}

}  // namespace sky
