#pragma once
// The weather map's high-layer cover on the GPU, for the high clouds' regional cover: one
// R16F image of WeatherMap::coverHigh as it is (the map's width x height, row 0 north, column 0
// west, over the map's region), persistent and imported into each frame's graph, uploaded only
// when the caller's revision changes. sky_high_clouds.comp samples it bilinearly, clamped to
// the edge, at the layer point's regionUv and takes cover 0 outside the region.
#include <cstdint>
#include <optional>

#include "engine/gpu/sampler.h"
#include "engine/graph/frame_graph.h"
#include "engine/weather/weather_map.h"

namespace sky {

class Context;

class RegionalCoverTexture {
public:
  // Creates the sampler; no image until the first addTo. `ctx` must outlive this object.
  explicit RegionalCoverTexture(const Context& ctx);

  // Imports the image into `graph` (this object must outlive graph.execute()). When
  // `revision` differs from the last call's (or on the first call) it first uploads
  // `map.coverHigh`, blocking until the copy finishes; with the same revision `map` is not
  // read. Internal error when the map has no high layer (coverHigh not width x height).
  ImageId addTo(FrameGraph& graph, const WeatherMap& map, uint64_t revision);

  // Linear filtering, clamp to edge (texel centres at (i + 0.5) / size, like the weather map).
  const Sampler& sampler() const { return mSampler; }
  // How many times addTo uploaded (tests, reports).
  uint64_t uploadCount() const { return mUploads; }

private:
  const Context& mCtx;
  Sampler mSampler;
  PersistentImage mCover;
  std::optional<uint64_t> mRevision;
  uint64_t mUploads = 0;
};

}  // namespace sky
