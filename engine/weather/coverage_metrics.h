#pragma once
// How well a top-down render's clouds match the weather map they came from (Lu et al. 2023,
// section 5: Dice between the CloudMap and the rendered clouds, Lu (28)). Both images are
// averaged over square blocks first: the map holds cover, not the noise's detail, so the
// comparison is between cover fractions at the block scale. `skyrender dsc` prints these.
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace sky {

struct CoverageOptions {
  int cell = 8;            // block size in pixels (>= 1); partial blocks at the edges count
  double threshold = 0.1;  // a block is cloudy when its average exceeds this, [0, 1)
};

struct CoverageMetrics {
  double dice = 1.0;  // Lu (28) 2|A n B| / (|A| + |B|) of the cloudy blocks; 1 when both are empty
  double meanAbsoluteError = 0.0;  // mean |rendered - map| of the block averages
  double correlation = 0.0;        // Pearson's r of the block averages; 0 when a side is constant
  uint64_t blocks = 0;             // how many blocks were compared
};

// Compares `rendered` (opacity) with `map` (cover), both width x height, one float per pixel,
// row-major. Internal error on sizes that do not match or a cell below 1.
CoverageMetrics compareCoverage(std::span<const float> rendered, std::span<const float> map,
                                int width, int height, const CoverageOptions& options);

// A top-down render's cloud opacity and the map cover it was rendered from.
struct RenderCoverage {
  int width = 0, height = 0;
  std::vector<float> opacity;  // layer clouds, channel A
  // 1 - (1 - low)(1 - mid) from weather.cover_low and weather.cover_mid: the cover of two
  // independent layers seen from above.
  std::vector<float> cover;
};

// Reads those layers from a render's EXR. BadInput naming the file and the missing layer
// ("render.exr: no layer clouds.A (render with camera.mode geographic_topdown)") or the
// layer that holds a NaN or infinity.
RenderCoverage readRenderCoverage(const std::filesystem::path& exr);

}  // namespace sky
