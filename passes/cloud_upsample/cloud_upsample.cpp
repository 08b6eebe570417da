#include "passes/cloud_upsample/cloud_upsample.h"

#include "passes/cloud_field/cloud_field.h"

namespace sky {

CloudUpsamplePass::CloudUpsamplePass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline(buildComputePipeline(ctx, compiler, "cloud_upsample.comp", kName)) {}

CloudUpsamplePass::Outputs CloudUpsamplePass::setup(GraphBuilder& b, const Inputs& in, Data& d) {
  d.inputs = in;
  b.read(in.clouds, Access::StorageReadCompute);
  b.read(in.depth, Access::StorageReadCompute);
  const CloudImages images = writeCloudImages(
      b, in.params.view.size.x, in.params.view.size.y,
      {"clouds_upsampled",
       "the clouds at the view's size: premultiplied radiance (RGB) and "
       "opacity (A)",
       "clouds_depth_upsampled",
       "the clouds' transmittance-weighted distance (m, R) and shell entry "
       "(m, G) at the view's size"});
  d.outputs.clouds = images.clouds;
  d.outputs.depth = images.depth;
  return d.outputs;
}

void CloudUpsamplePass::execute(PassContext& ctx, const Data& d) const {
  const auto& size = d.inputs.params.view.size;
  ctx.dispatch(mPipeline,
               {Binding::of(CLOUD_UPSAMPLE_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
                Binding::of(CLOUD_UPSAMPLE_BINDING_CLOUDS, d.inputs.clouds),
                Binding::of(CLOUD_UPSAMPLE_BINDING_DEPTH, d.inputs.depth),
                Binding::of(CLOUD_UPSAMPLE_BINDING_OUT_CLOUDS, d.outputs.clouds),
                Binding::of(CLOUD_UPSAMPLE_BINDING_OUT_DEPTH, d.outputs.depth)},
               mPipeline.groupsX(size.x), mPipeline.groupsY(size.y));
}

}  // namespace sky
