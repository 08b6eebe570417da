#include "engine/weather/coverage_metrics.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.h"
#include "engine/io/exr.h"

namespace sky {
namespace {

// Block averages of a width x height image over cell x cell blocks, row-major; an edge
// block averages the pixels it has.
std::vector<double> blockAverages(std::span<const float> image, int width, int height, int cell) {
  const int bw = (width + cell - 1) / cell, bh = (height + cell - 1) / cell;
  std::vector<double> sum(size_t(bw) * size_t(bh), 0.0), count(sum.size(), 0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t b = size_t(y / cell) * size_t(bw) + size_t(x / cell);
      sum[b] += image[size_t(y) * size_t(width) + size_t(x)];
      count[b] += 1.0;
    }
  for (size_t b = 0; b < sum.size(); ++b) sum[b] /= count[b];
  return sum;
}

// The channel `channel` of layer `layer`, one float per pixel.
std::vector<float> channelOf(const LayeredImage& image, const std::string& file,
                             const std::string& layer, const std::string& channel) {
  const std::string name = layer + "." + channel;
  const ImageLayer* l = image.find(layer);
  const size_t offset =
      l ? size_t(std::find(l->channels.begin(), l->channels.end(), channel) - l->channels.begin())
        : 0;
  if (!l || offset == l->channels.size())
    inputError(file + ": no layer " + name + " (render with camera.mode geographic_topdown)");
  const size_t stride = l->channels.size();
  std::vector<float> out(size_t(image.width) * size_t(image.height));
  for (size_t i = 0; i < out.size(); ++i) {
    out[i] = l->pixels[i * stride + offset];
    if (!std::isfinite(out[i])) inputError(file + ": " + name + " holds a NaN or infinite value");
  }
  return out;
}

}  // namespace

CoverageMetrics compareCoverage(std::span<const float> rendered, std::span<const float> map,
                                int width, int height, const CoverageOptions& options) {
  const size_t pixels = size_t(std::max(width, 0)) * size_t(std::max(height, 0));
  if (width < 1 || height < 1 || rendered.size() != pixels || map.size() != pixels)
    internalError("compareCoverage: images of different or empty sizes");
  if (options.cell < 1) internalError("compareCoverage: cell below 1");
  const std::vector<double> a = blockAverages(rendered, width, height, options.cell);
  const std::vector<double> b = blockAverages(map, width, height, options.cell);
  const double n = double(a.size());

  CoverageMetrics m;
  m.blocks = a.size();
  // Lu (28) on the thresholded blocks.
  size_t both = 0, cloudyA = 0, cloudyB = 0;
  double absSum = 0.0, meanA = 0.0, meanB = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const bool ca = a[i] > options.threshold, cb = b[i] > options.threshold;
    cloudyA += ca;
    cloudyB += cb;
    both += ca && cb;
    absSum += std::abs(a[i] - b[i]);
    meanA += a[i];
    meanB += b[i];
  }
  m.dice = cloudyA + cloudyB == 0 ? 1.0 : 2.0 * double(both) / double(cloudyA + cloudyB);
  m.meanAbsoluteError = absSum / n;
  meanA /= n;
  meanB /= n;
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - meanA) * (b[i] - meanB);
    saa += (a[i] - meanA) * (a[i] - meanA);
    sbb += (b[i] - meanB) * (b[i] - meanB);
  }
  // Constant within rounding (a standard deviation below 1e-9): r is undefined, report 0.
  const double flat = n * 1e-18;
  m.correlation = saa <= flat || sbb <= flat ? 0.0 : sab / std::sqrt(saa * sbb);
  return m;
}

RenderCoverage readRenderCoverage(const std::filesystem::path& exr) {
  const std::string file = exr.string();
  const LayeredImage image = readExr(exr);
  RenderCoverage out;
  out.width = image.width;
  out.height = image.height;
  out.opacity = channelOf(image, file, "clouds", "A");
  const std::vector<float> low = channelOf(image, file, "weather", "cover_low");
  const std::vector<float> mid = channelOf(image, file, "weather", "cover_mid");
  out.cover.resize(low.size());
  for (size_t i = 0; i < low.size(); ++i) out.cover[i] = 1.0f - (1.0f - low[i]) * (1.0f - mid[i]);
  return out;
}

}  // namespace sky
