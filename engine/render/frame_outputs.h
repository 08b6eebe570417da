#pragma once
// The outputs of a frame: which of its images are read back (the EXR's layers, the display
// codes, debug images by their names) and how they become a RenderedFrame. One of the
// Renderer's jobs, beside the sky (sky_layer.h), the clouds (volumetric_cloud_layer.h) and the
// cloud history (cloud_reuse.h).
#include <string>
#include <utility>
#include <vector>

#include "engine/graph/frame_graph.h"
#include "engine/render/frame_types.h"

namespace sky {

struct WeatherMap;

// What a frame's outputs are read from: its images, and their read-backs once requested.
struct FramePlan {
  ImageId beauty, sky, highClouds, clouds, cloudsDepth, display;
  // With output.perception: the composite's perception image and the clouds' hits (invalid
  // without volumetric clouds).
  ImageId perception, cloudHit;
  // Their read-backs, as requestOutputs asked for them (invalid: not read back), and the
  // debug images'.
  struct Outputs {
    OutputId beauty, sky, highClouds, clouds, cloudsDepth, display, perception, cloudHit;
    std::vector<std::pair<OutputId, GraphImage>> debug;
  } outputs;
  const WeatherMap* weather = nullptr;  // a top-down view's map, for its "weather" layer
  bool reuseStep = false;  // the frame took a step of the cloud history: commit it once run
};

// What a debug view shows of an image of the frame's graph.
DebugImageInfo debugImageInfo(const GraphImage& g);

// Asks `graph` to read back what `options` wants of `plan`. `prefix` labels a view's outputs
// in a frame of several ("view1/"), for errors and dumps.
void requestOutputs(FrameGraph& graph, FramePlan& plan, const RenderOptions& options,
                    const std::string& prefix = "");
// The layers, display and debug images of `plan` from `result` (the frame's read-backs).
void collectOutputs(RenderedFrame& out, const FrameResult& result, const FrameGraph& graph,
                    const FramePlan& plan, const RenderOptions& options);

}  // namespace sky
