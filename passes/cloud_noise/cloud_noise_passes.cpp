#include "passes/cloud_noise/cloud_noise_passes.h"

#include <memory>

#include "engine/core/error.h"
#include "engine/graph/pass_context.h"
#include "engine/shader/shader_compiler.h"

namespace sky {

CloudNoiseBakePass::CloudNoiseBakePass(const Context& ctx, ShaderCompiler& compiler,
                                       const std::string& name)
    : mName(name), mPipeline(ctx, compileForDevice(ctx, compiler, name + ".comp"), name) {}

CloudNoiseBakePass::Outputs CloudNoiseBakePass::addTo(FrameGraph& graph,
                                                      const Inputs& inputs) const {
  if (inputs.params.size.x == 0) internalError(mName + ": empty texture");
  (void)mPipeline.get();  // created now, before the graph records
  // The execute callback owns this use's inputs; setup's handle goes in once it exists.
  auto use = std::make_shared<Inputs>(inputs);
  GraphBuilder b = graph.addPass(inputs.label ? inputs.label : mName,
                                 [this, use](PassContext& ctx) { execute(ctx, *use); });
  use->target = b.write(inputs.target, Access::StorageWriteCompute);
  b.sideEffect();
  return {use->target};
}

void CloudNoiseBakePass::execute(PassContext& ctx, const Inputs& inputs) const {
  const uint32_t n = inputs.params.size.x;
  const bool volume = ctx.image(inputs.target).desc().dim == ImageDim::Tex3D;
  const ComputePipeline& pipeline = mPipeline.get();
  ctx.dispatch(pipeline, {Binding::of(CLOUD_NOISE_BINDING_OUT, inputs.target)}, pipeline.groupsX(n),
               pipeline.groupsY(n), volume ? pipeline.groupsZ(n) : 1, &inputs.params,
               sizeof inputs.params);
}

}  // namespace sky
