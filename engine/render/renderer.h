#pragma once
// Scene in, scene-linear layered image out: builds one frame graph per frame from the
// passes, executes it and collects the main image and AOVs. Owns the passes' pipelines and
// the star catalogue on the GPU, so create it once and render many frames.
#include <string>

#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/io/exr.h"
#include "engine/lighting/lighting_state.h"
#include "engine/scene/scene.h"
#include "passes/atmosphere_composite/atmosphere_composite.h"
#include "passes/star_field/star_field.h"

namespace sky {

class Context;
class ShaderCompiler;

struct RenderedFrame {
  LayeredImage image;      // layer "" = beauty (R,G,B,A); "sky" = clear sky (R,G,B)
  FrameResult frame;       // per-pass GPU timings, wall time
  std::string graphDot;    // the compiled graph with timings (for --dump-graph)
  LightingState lighting;  // the sun, moon, palette and night state the frame was lit by
};

class Renderer {
public:
  // Loads the star catalogue from configs/stars/ (under dataRoot()).
  Renderer(const Context& ctx, ShaderCompiler& compiler);
  // Renders `scene` at its output size as seen at `time` (one frame of scene.time).
  // Errors: sky::Error (BadInput when the size is impossible on this device or does not fit
  // in memory).
  RenderedFrame render(const Scene& scene, const IsoTime& time);
  // The first (or only) frame of the scene's time.
  RenderedFrame render(const Scene& scene) { return render(scene, scene.time.start); }

private:
  GraphRuntime mRuntime;
  StarFieldPass mStars;
  AtmosphereCompositePass mComposite;
};

}  // namespace sky
