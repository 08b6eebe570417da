#include "apps/common/debug_view.h"

#include <algorithm>
#include <cmath>

namespace sky {
namespace {

uint8_t code(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  // sRGB's transfer function: a debug image is viewed on the same displays as the frame.
  const float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return static_cast<uint8_t>(std::lround(s * 255.0f));
}

// The value below which `share` of the finite values lie (0 when there are none).
float quantile(std::vector<float> values, double share) {
  values.erase(
      std::remove_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); }),
      values.end());
  if (values.empty()) return 0.0f;
  const size_t k = std::min(values.size() - 1, static_cast<size_t>(share * double(values.size())));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

}  // namespace

const char* debugViewName(DebugView view) {
  switch (view) {
    case DebugView::Color:
      return "colour";
    case DebugView::Scalar:
      return "scalar";
    case DebugView::Normals:
      return "normals";
    case DebugView::Depth:
      return "depth";
    case DebugView::Heat:
      return "heat";
  }
  return "?";
}

void falseColour(float t, uint8_t rgb[3]) {
  // Five stops of a viridis-like ramp, interpolated linearly in sRGB codes.
  static const float kStops[5][3] = {{0.07f, 0.02f, 0.33f},
                                     {0.18f, 0.36f, 0.55f},
                                     {0.13f, 0.57f, 0.55f},
                                     {0.48f, 0.80f, 0.30f},
                                     {0.99f, 0.91f, 0.14f}};
  t = std::clamp(std::isfinite(t) ? t : 0.0f, 0.0f, 1.0f) * 4.0f;
  const int i = std::min(3, static_cast<int>(t));
  const float f = t - float(i);
  for (int c = 0; c < 3; ++c)
    rgb[c] = static_cast<uint8_t>(
        std::lround(255.0f * (kStops[i][c] + (kStops[i + 1][c] - kStops[i][c]) * f)));
}

DisplayTile debugDisplay(const DebugImage& image, uint32_t maxSlices) {
  const ImageLayer& layer = image.image.layers.at(0);
  const size_t channels = layer.channels.size();
  const uint32_t depth = std::max(image.info.depth, 1u);
  const uint32_t sliceWidth = static_cast<uint32_t>(image.image.width) / depth;
  const uint32_t height = static_cast<uint32_t>(image.image.height);
  const uint32_t slices = std::min(depth, std::max(maxSlices, 1u));
  std::vector<uint32_t> picked(slices);
  for (uint32_t s = 0; s < slices; ++s)
    picked[s] = slices == depth ? s : static_cast<uint32_t>((s + 0.5) * depth / slices);

  DisplayTile tile;
  tile.width = sliceWidth * slices;
  tile.height = height;
  tile.rgba.assign(size_t(tile.width) * tile.height * 4, 255);
  auto value = [&](uint32_t x, uint32_t y, size_t c) {
    const uint32_t s = x / sliceWidth;
    const size_t sx = size_t(picked[s]) * sliceWidth + x % sliceWidth;
    return c < channels ? layer.pixels[(size_t(y) * image.image.width + sx) * channels + c] : 0.0f;
  };
  std::vector<float> first;
  first.reserve(size_t(tile.width) * tile.height);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < tile.width; ++x) first.push_back(value(x, y, 0));

  const DebugView view = image.info.view;
  if (view == DebugView::Color || view == DebugView::Normals) {
    float scale = 1.0f;
    if (view == DebugView::Color) {
      // Exposed so the brightest 1 % clips: radiance spans nine decades from night to noon.
      std::vector<float> peaks;
      peaks.reserve(first.size());
      for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < tile.width; ++x) {
          float m = 0.0f;
          for (size_t c = 0; c < std::min<size_t>(channels, 3); ++c)
            m = std::max(m, value(x, y, c));
          peaks.push_back(m);
        }
      const float p99 = quantile(std::move(peaks), 0.99);
      scale = p99 > 0.0f ? 1.0f / p99 : 1.0f;
    }
    for (uint32_t y = 0; y < height; ++y)
      for (uint32_t x = 0; x < tile.width; ++x) {
        uint8_t* px = &tile.rgba[(size_t(y) * tile.width + x) * 4];
        for (size_t c = 0; c < 3; ++c) {
          // One channel is grey; two are red and green.
          const float v = channels == 1 ? value(x, y, 0) : c < channels ? value(x, y, c) : 0.0f;
          // Normals: xyz in -1..1 to 0..1, shown as the codes themselves (no transfer curve).
          px[c] = view == DebugView::Normals
                      ? static_cast<uint8_t>(
                            std::lround(255.0f * std::clamp(0.5f * v + 0.5f, 0.0f, 1.0f)))
                      : code(v * scale);
        }
      }
    return tile;
  }

  // False colour of the first channel over its range; depth on a log scale, none black.
  tile.legend = true;
  const bool log = view == DebugView::Depth;
  std::vector<float> range;
  for (float v : first)
    if (std::isfinite(v) && (!log || v > 0.0f)) range.push_back(v);
  tile.low = view == DebugView::Heat ? 0.0f : quantile(range, 0.0);
  tile.high = quantile(range, 1.0);
  if (view == DebugView::Depth) tile.unit = "m";
  const float lo = log ? std::log(std::max(tile.low, 1e-3f)) : tile.low;
  const float hi = log ? std::log(std::max(tile.high, 1e-3f)) : tile.high;
  for (size_t i = 0; i < first.size(); ++i) {
    uint8_t* px = &tile.rgba[i * 4];
    const float v = first[i];
    if (log && !(v > 0.0f)) {
      px[0] = px[1] = px[2] = 0;
      continue;
    }
    const float x = log ? std::log(v) : v;
    float t = hi > lo ? (x - lo) / (hi - lo) : 0.5f;
    if (log) t = 1.0f - t;  // near bright
    falseColour(t, px);
  }
  return tile;
}

}  // namespace sky
