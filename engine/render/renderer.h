#pragma once
// Scene in, scene-linear layered image out: builds one frame graph per frame from the
// passes, executes it and collects the main image and AOVs. Owns the passes' pipelines,
// so create it once and render many frames.
#include <string>

#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/io/exr.h"
#include "engine/lighting/sun_position.h"
#include "engine/scene/scene.h"
#include "passes/atmosphere_composite/atmosphere_composite.h"

namespace sky {

class Context;
class ShaderCompiler;

struct RenderedFrame {
  LayeredImage image;        // layer "" = beauty (R,G,B,A); "sky" = clear sky (R,G,B)
  FrameResult frame;         // per-pass GPU timings, wall time
  std::string graphDot;      // the compiled graph with timings (for --dump-graph)
  HorizontalPosition sun{};  // where the sun was placed
  bool sunFromTime = false;  // true when computed from time and place, not the override
};

class Renderer {
public:
  Renderer(const Context& ctx, ShaderCompiler& compiler);
  // Renders one frame of `scene` at its output size. Errors: sky::Error (BadInput when the
  // size is impossible on this device or does not fit in memory).
  RenderedFrame render(const Scene& scene);

private:
  GraphRuntime mRuntime;
  AtmosphereCompositePass mComposite;
};

// The sun for `scene`: its explicit azimuth/elevation, or the position for its time and place.
HorizontalPosition resolveSun(const Scene& scene, bool* fromTime = nullptr);

}  // namespace sky
