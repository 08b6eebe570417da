#pragma once
// The clouds marched at reduced resolution brought to the view's (shaders/cloud_upsample.comp;
// clouds.temporal.resolution half): a depth-aware bilinear upsampling guided by where each
// pixel's ray reaches the cloud shells, so the horizon and the ground stay sharp.
#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "shaders/common/cloud_upsample_shared.h"

namespace sky {

class Context;
class ShaderCompiler;

class CloudUpsamplePass {
public:
  static constexpr const char* kName = "cloud_upsample";
  struct Inputs {
    shared::CloudUpsampleParams params{};
    ImageId clouds;  // RGBA32F at params.source's size
    ImageId depth;   // RG32F: depth (m), where the ray reaches the shells
  };
  struct Outputs {
    ImageId clouds;  // RGBA32F at params.view's size
    ImageId depth;   // RG32F
  };

  CloudUpsamplePass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add).
  struct Data {
    Inputs inputs{};
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  ComputePipeline mPipeline;
};

}  // namespace sky
