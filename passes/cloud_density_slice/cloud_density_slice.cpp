#include "passes/cloud_density_slice/cloud_density_slice.h"

namespace sky {

CloudDensitySlicePass::CloudDensitySlicePass(const Context& ctx, ShaderCompiler& compiler)
    : mPipelines(ctx, compiler, "cloud_density_slice.comp", kName) {}

CloudDensitySlicePass::Outputs CloudDensitySlicePass::setup(GraphBuilder& b, const Inputs& in,
                                                            Data& d) {
  d.inputs = in;
  readCloudTextures(b, in.textures);
  ImageDesc desc;
  desc.width = kWidth;
  desc.height = kHeight;
  desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  desc.name = "cloud_density_slice";
  desc.about =
      "a vertical cut along the camera's heading, 60 km ahead (across) by sea level to above "
      "the clouds (down): R density, G cover, B type, A layer";
  desc.view = DebugView::Scalar;  // the density: the other channels explain it
  desc.channels = "density,cover,type,layer";
  d.outputs.slice = b.write(b.create(desc), Access::StorageWriteCompute);
  return d.outputs;
}

void CloudDensitySlicePass::execute(PassContext& ctx, const Data& d) const {
  std::vector<Binding> bindings = cloudTextureBindings(d.inputs.textures);
  bindings.insert(bindings.end(),
                  {Binding::of(VOLUMETRIC_CLOUDS_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
                   Binding::of(CLOUD_SLICE_BINDING_IMAGE, d.outputs.slice)});
  const ComputePipeline& pipeline = mPipelines.get(d.inputs.variant);
  ctx.dispatch(pipeline, bindings, pipeline.groupsX(kWidth), pipeline.groupsY(kHeight));
}

}  // namespace sky
