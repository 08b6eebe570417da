#pragma once
// The weather map on the GPU, for the volumetric clouds and the high clouds: the map itself
// (RGBA16F, the WeatherMap's texels as they are: low, mid, type, density scale), its coarse
// max-cover map for empty-space skipping (engine/weather/coarse_cover.h) and, for a forecast,
// the high layer's cover (R16F, WeatherMap::coverHigh). Each is a RevisionedImage: uploaded by
// a graph transfer pass only when the map's revision changes. One sampler serves all three.
#include <cstdint>

#include "engine/gpu/sampler.h"
#include "engine/render/revisioned_image.h"
#include "engine/weather/weather_map.h"

namespace sky {

class Context;

class WeatherTextures {
public:
  struct Clouds {
    ImageId map;     // RGBA16F, the WeatherMap's size: low, mid, type, density scale
    ImageId coarse;  // RGBA16F, coarseCoverSize: max low, max mid, max of both, 0
  };

  // `ctx` must outlive this object.
  explicit WeatherTextures(const Context& ctx);

  // The map and its coarse map for the volumetric clouds, imported into `graph` and uploaded
  // first when `revision` (the map's: CloudLayers::mapRevision) is not what they hold. This
  // object must outlive graph.execute(). Internal error for an empty map.
  Clouds addClouds(FrameGraph& graph, const WeatherMap& map, uint64_t revision);
  // The high layer's cover for the high clouds' regional cover (row 0 north, column 0 west,
  // over the map's region), the same way. Internal error when the map has no high layer.
  ImageId addHighCover(FrameGraph& graph, const WeatherMap& map, uint64_t revision);

  // Linear filtering, clamp to edge (texel centres at (i + 0.5) / size), for all three.
  const Sampler& sampler() const { return mSampler; }
  // How many frames uploaded the map (tests, reports).
  uint64_t mapUploadCount() const { return mMap.uploadCount(); }
  uint64_t highCoverUploadCount() const { return mHighCover.uploadCount(); }

private:
  Sampler mSampler;
  RevisionedImage mMap;
  RevisionedImage mCoarse;
  RevisionedImage mHighCover;
};

}  // namespace sky
