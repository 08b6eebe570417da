#include "passes/cloud_upsample/cloud_upsample.h"

namespace sky {

CloudUpsamplePass::CloudUpsamplePass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline(buildComputePipeline(ctx, compiler, "cloud_upsample.comp", kName)) {}

CloudUpsamplePass::Outputs CloudUpsamplePass::setup(GraphBuilder& b, const Inputs& in) {
  mInputs = in;
  b.read(in.clouds, Access::StorageReadCompute);
  b.read(in.depth, Access::StorageReadCompute);
  ImageDesc desc;
  desc.width = in.params.view.size.x;
  desc.height = in.params.view.size.y;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.name = "clouds_upsampled";
  desc.about = "the clouds at the view's size: premultiplied radiance (RGB) and opacity (A)";
  mOutputs.clouds = b.write(b.create(desc), Access::StorageWriteCompute);
  desc.format = VK_FORMAT_R32G32_SFLOAT;
  desc.name = "clouds_depth_upsampled";
  desc.about =
      "the clouds' transmittance-weighted distance (m, R) and shell entry (m, G) at the view's "
      "size";
  desc.view = DebugView::Depth;
  desc.channels = "depth,shell_entry";
  mOutputs.depth = b.write(b.create(desc), Access::StorageWriteCompute);
  return mOutputs;
}

void CloudUpsamplePass::execute(PassContext& ctx) const {
  const auto& size = mInputs.params.view.size;
  ctx.dispatch(mPipeline,
               {Binding::of(CLOUD_UPSAMPLE_BINDING_PARAMS, ctx.uniform(mInputs.params)),
                Binding::of(CLOUD_UPSAMPLE_BINDING_CLOUDS, mInputs.clouds),
                Binding::of(CLOUD_UPSAMPLE_BINDING_DEPTH, mInputs.depth),
                Binding::of(CLOUD_UPSAMPLE_BINDING_OUT_CLOUDS, mOutputs.clouds),
                Binding::of(CLOUD_UPSAMPLE_BINDING_OUT_DEPTH, mOutputs.depth)},
               mPipeline.groupsX(size.x), mPipeline.groupsY(size.y));
}

}  // namespace sky
