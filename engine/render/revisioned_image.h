#pragma once
// An image the frame samples whose texels come from the CPU and change rarely (the weather
// map, its coarse cover, the high layer's cover): persistent, imported into each frame's
// graph, and refilled by a graph transfer pass (FrameGraph::upload) only in a frame whose
// revision differs from the one the image holds. A frame that fails leaves the old revision
// recorded, so the next frame uploads again.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "engine/graph/frame_graph.h"

namespace sky {

class Context;

class RevisionedImage {
public:
  // `desc` gives the name, about, format and debug view; the size comes with each addTo and
  // the usage is set here (sampled, upload destination, read back for debug views and tests).
  // `ctx` must outlive this object.
  RevisionedImage(const Context& ctx, ImageDesc desc);

  // Imports the image into `graph` (this object must outlive graph.execute()). When
  // `revision` differs from what the image holds (or on the first call) it (re)creates the
  // image at width x height if its size differs and adds the pass "upload NAME" that fills it
  // with texels(), which is called only then. The image holds `revision` once the frame has
  // executed. Returns the handle that the frame's passes read.
  ImageId addTo(FrameGraph& graph, uint64_t revision, uint32_t width, uint32_t height,
                const std::function<std::vector<float>()>& texels);

  // How many frames ran an upload (tests, reports).
  uint64_t uploadCount() const { return mUploads; }

private:
  const Context& mCtx;
  ImageDesc mDesc;
  PersistentImage mImage;
  std::optional<uint64_t> mRevision;  // what the image holds
  uint64_t mUploads = 0;
};

}  // namespace sky
