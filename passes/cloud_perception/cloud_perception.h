#pragma once
// The clouds' ground truth per pixel (shaders/cloud_perception.comp): the optical depth of the
// volumetric clouds along each pixel's centre ray, unbounded, the distance at which it passes
// a tenth, and the layer and cloud type there. It marches the raymarch's own density field
// (the cloud pass's parameters and textures) without light, jitter or early exit. The
// composite's perception variant turns it into labels (passes/atmosphere_composite).
// docs/outputs.md, "Perception layers".
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "passes/cloud_field/cloud_field.h"

namespace sky {

class CloudPerceptionPass {
public:
  static constexpr const char* kName = "cloud_perception";
  struct Inputs {
    // The cloud pass's uniforms with the view at the output's size (a temporal frame marches
    // at half of it).
    shared::CloudParams params{};
    CloudVariant variant;  // an observer's (CloudFrame::Observer)
    CloudTextures textures;
  };
  struct Outputs {
    ImageId hit;  // RGBA32F at the view's size: r optical depth, g hit distance (m, +inf: none),
                  // b layer at the hit (0 low, 1 mid, -1 none), a the map's type there
  };

  CloudPerceptionPass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add).
  struct Data {
    const ComputePipeline* pipeline = nullptr;
    Inputs inputs{};
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  CloudPipelines mPipelines;
};

}  // namespace sky
