#include "passes/cloud_denoise/cloud_denoise.h"

#include "passes/cloud_field/cloud_field.h"

namespace sky {

CloudDenoisePass::CloudDenoisePass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline(buildComputePipeline(ctx, compiler, "cloud_denoise.comp", kName)) {}

CloudDenoisePass::Outputs CloudDenoisePass::setup(GraphBuilder& b, const Inputs& in, Data& d) {
  d.inputs = in;
  b.read(in.clouds, Access::StorageReadCompute);
  b.read(in.depth, Access::StorageReadCompute);
  const CloudImages images = writeCloudImages(
      b, in.params.view.size.x, in.params.view.size.y,
      {"clouds_denoised",
       "the clouds with the march's grain filtered out: premultiplied "
       "radiance (RGB) and opacity (A)",
       "clouds_depth_denoised",
       "the clouds' transmittance-weighted distance (m, R), filtered with "
       "them, and shell entry (m, G)"});
  d.outputs.clouds = images.clouds;
  d.outputs.depth = images.depth;
  return d.outputs;
}

void CloudDenoisePass::execute(PassContext& ctx, const Data& d) const {
  const auto& size = d.inputs.params.view.size;
  ctx.dispatch(mPipeline,
               {Binding::of(CLOUD_DENOISE_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
                Binding::of(CLOUD_DENOISE_BINDING_CLOUDS, d.inputs.clouds),
                Binding::of(CLOUD_DENOISE_BINDING_DEPTH, d.inputs.depth),
                Binding::of(CLOUD_DENOISE_BINDING_OUT_CLOUDS, d.outputs.clouds),
                Binding::of(CLOUD_DENOISE_BINDING_OUT_DEPTH, d.outputs.depth)},
               mPipeline.groupsX(size.x), mPipeline.groupsY(size.y));
}

}  // namespace sky
