#pragma once
// The weather map on the GPU: the map itself (RGBA16F, the WeatherMap's texels as they are)
// and a coarse conservative "max cover" map for empty-space skipping, both persistent images
// imported into each frame's graph. Uploaded only when the caller's revision changes.
#include <cstdint>
#include <optional>

#include <glm/vec2.hpp>

#include "engine/gpu/sampler.h"
#include "engine/graph/frame_graph.h"
#include "engine/weather/weather_map.h"

namespace sky {

class Context;

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

class WeatherTexture {
public:
  struct Outputs {
    ImageId map;     // RGBA16F, the WeatherMap's size: low, mid, type, density scale
    ImageId coarse;  // RGBA16F, coarseCoverSize: max low, max mid, max of both, 0
  };

  // Creates the sampler; no images until the first addTo. `ctx` must outlive this object.
  explicit WeatherTexture(const Context& ctx);

  // Imports the two images into `graph` (this object must outlive graph.execute()). When
  // `revision` differs from the last call's (or on the first call) it first uploads `map`
  // and its coarseCoverMap, blocking until the copies finish; with the same revision the
  // images are imported as they are and `map` is not read. Internal error for an empty map.
  Outputs addTo(FrameGraph& graph, const WeatherMap& map, uint64_t revision);

  // Linear filtering, clamp to edge: for both images (texel centres at (i + 0.5) / size).
  const Sampler& sampler() const { return mSampler; }
  // How many times addTo uploaded (tests, reports).
  uint64_t uploadCount() const { return mUploads; }

private:
  void upload(const WeatherMap& map);

  const Context& mCtx;
  Sampler mSampler;
  PersistentImage mMap;
  PersistentImage mCoarse;
  std::optional<uint64_t> mRevision;
  uint64_t mUploads = 0;
};

}  // namespace sky
