#include "passes/cloud_upsample/cloud_upsample.h"

namespace sky {

CloudUpsamplePass::CloudUpsamplePass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline(buildComputePipeline(ctx, compiler, "cloud_upsample.comp", kName)) {}

CloudUpsamplePass::Outputs CloudUpsamplePass::setup(GraphBuilder& b, const Inputs& in, Data& d) {
  d.inputs = in;
  b.read(in.clouds, Access::StorageReadCompute);
  b.read(in.depth, Access::StorageReadCompute);
  ImageDesc desc;
  desc.width = in.params.view.size.x;
  desc.height = in.params.view.size.y;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.name = "clouds_upsampled";
  desc.about = "the clouds at the view's size: premultiplied radiance (RGB) and opacity (A)";
  d.outputs.clouds = b.write(b.create(desc), Access::StorageWriteCompute);
  desc.format = VK_FORMAT_R32G32_SFLOAT;
  desc.name = "clouds_depth_upsampled";
  desc.about =
      "the clouds' transmittance-weighted distance (m, R) and shell entry (m, G) at the view's "
      "size";
  desc.view = DebugView::Depth;
  desc.channels = "depth,shell_entry";
  d.outputs.depth = b.write(b.create(desc), Access::StorageWriteCompute);
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
