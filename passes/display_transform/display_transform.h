#pragma once
// The GPU display path (shaders/display_transform.comp): the beauty through the night look,
// the exposure and the OCIO view baked into a 3D table (engine/color/display_lut.h), into an
// 8-bit display image. A window or a benchmark frame reads that back (a quarter of the
// beauty's bytes) instead of running OCIO over the float image on the CPU.
#include <string>

#include "engine/gpu/compute_pipeline.h"
#include "engine/gpu/sampler.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "shaders/common/display_transform_shared.h"

namespace sky {

class Context;
class OcioOutput;
class ShaderCompiler;

// What the display path takes from the scene and the frame.
struct DisplayTransformSettings {
  const OcioOutput* ocio = nullptr;  // bakes the table; must outlive the pass's frames
  std::string display, view;         // output.display, output.view
  double exposureEv = 0.0;           // the frame's whole exposure
  bool nightLook = true;             // output.night_look
};

class DisplayTransformPass {
public:
  static constexpr const char* kName = "display_transform";
  struct Inputs {
    DisplayTransformSettings settings;
    ImageId beauty;                  // RGBA32F scene-linear
    uint32_t width = 0, height = 0;  // the beauty's size
    // Where the codes go: an RGBA8 UNORM storage image of the beauty's size that outlives
    // the frame (skyview's window image, imported with FrameGraph::importExternal). Invalid:
    // an image of the frame's own, to read back.
    ImageId target;
  };
  struct Outputs {
    ImageId display;  // RGBA8 UNORM display-referred, the beauty's size (Inputs::target's
                      // new version when given)
  };

  DisplayTransformPass(const Context& ctx, ShaderCompiler& compiler);
  // Bakes and uploads the display/view's table on first use (kept for the next frames).
  Outputs addTo(FrameGraph& graph, const Inputs& inputs);
  // One use's data, in the frame graph: once per view.
  struct Data {
    shared::DisplayTransformParams params{};
    ImageId lut, beauty;
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  const Context& mCtx;
  ComputePipeline mPipeline;
  Sampler mSampler;      // linear, clamp
  PersistentImage mLut;  // RGBA32F DisplayLut::kSize^3
  std::string mLutKey;   // display + view it was baked for
};

}  // namespace sky
