#pragma once
// A still's clouds with their march's grain filtered out (shaders/cloud_denoise.comp;
// clouds.denoise, frames with no temporal reuse): a binomial 3 x 3 mean of the neighbours
// alike in depth and in where their rays reach the cloud shells, so outlines, the horizon and
// the ground stay sharp.
#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "shaders/common/cloud_denoise_shared.h"

namespace sky {

class Context;
class ShaderCompiler;

class CloudDenoisePass {
public:
  static constexpr const char* kName = "cloud_denoise";
  struct Inputs {
    shared::CloudDenoiseParams params{};
    ImageId clouds;  // RGBA32F at params.view's size: premultiplied radiance, opacity
    ImageId depth;   // RG32F: depth (m), where the ray reaches the shells
  };
  struct Outputs {
    ImageId clouds;  // RGBA32F, the same size
    ImageId depth;   // RG32F
  };

  CloudDenoisePass(const Context& ctx, ShaderCompiler& compiler);
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
