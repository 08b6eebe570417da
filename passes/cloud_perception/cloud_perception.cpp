#include "passes/cloud_perception/cloud_perception.h"

#include "engine/core/error.h"
#include "shaders/common/cloud_perception_shared.h"

namespace sky {

CloudPerceptionPass::CloudPerceptionPass(const Context& ctx, ShaderCompiler& compiler)
    : mPipelines(ctx, compiler, "cloud_perception.comp", kName) {}

CloudPerceptionPass::Outputs CloudPerceptionPass::setup(GraphBuilder& b, const Inputs& in,
                                                        Data& d) {
  if (in.variant.frame != CloudFrame::Observer)
    internalError("cloud_perception: a top-down frame has no observer's rays");
  d.inputs = in;
  d.pipeline = &mPipelines.get(in.variant);
  readCloudTextures(b, in.textures);
  ImageDesc desc;
  desc.width = in.params.view.size.x;
  desc.height = in.params.view.size.y;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.name = "cloud_perception";
  desc.about =
      "the clouds' ground truth along each pixel's centre ray: R optical depth (unbounded), G "
      "distance to where it passes 0.1 (m, inf: never), B layer there, A type there";
  desc.view = DebugView::Scalar;  // the optical depth: the other channels explain it
  desc.channels = "optical_depth,distance,layer,type";
  d.outputs.hit = b.write(b.create(desc), Access::StorageWriteCompute);
  return d.outputs;
}

void CloudPerceptionPass::execute(PassContext& ctx, const Data& d) const {
  std::vector<Binding> bindings = cloudTextureBindings(d.inputs.textures);
  bindings.insert(bindings.end(),
                  {Binding::of(VOLUMETRIC_CLOUDS_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
                   Binding::of(CLOUD_PERCEPTION_BINDING_HIT, d.outputs.hit)});
  const uint32_t w = d.inputs.params.view.size.x, h = d.inputs.params.view.size.y;
  ctx.dispatch(*d.pipeline, bindings, d.pipeline->groupsX(w), d.pipeline->groupsY(h));
}

}  // namespace sky
