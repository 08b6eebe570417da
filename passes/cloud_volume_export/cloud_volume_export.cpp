#include "passes/cloud_volume_export/cloud_volume_export.h"

namespace sky {

CloudVolumeExportPass::CloudVolumeExportPass(const Context& ctx, ShaderCompiler& compiler)
    : mPipelines(ctx, compiler, "cloud_volume_export.comp", kName) {}

CloudVolumeExportPass::Outputs CloudVolumeExportPass::setup(GraphBuilder& b, const Inputs& in) {
  mInputs = in;
  mPipeline = &mPipelines.get(in.variant);
  readCloudTextures(b, in.textures);
  ImageDesc desc;
  desc.dim = ImageDim::Tex3D;
  desc.width = in.box.voxels.x;
  desc.height = in.box.voxels.y;
  desc.depth = in.box.voxels.z;
  desc.format = VK_FORMAT_R32_SFLOAT;
  desc.name = "cloud_volume";
  mOutputs.grid = b.write(b.create(desc), Access::StorageWriteCompute);
  return mOutputs;
}

void CloudVolumeExportPass::execute(PassContext& ctx) const {
  const glm::uvec4& n = mInputs.box.voxels;
  std::vector<Binding> bindings = cloudTextureBindings(mInputs.textures);
  bindings.insert(bindings.end(),
                  {Binding::of(VOLUMETRIC_CLOUDS_BINDING_PARAMS, ctx.uniform(mInputs.params)),
                   Binding::of(CLOUD_VOLUME_EXPORT_BINDING_PARAMS, ctx.uniform(mInputs.box)),
                   Binding::of(CLOUD_VOLUME_EXPORT_BINDING_GRID, mOutputs.grid)});
  ctx.dispatch(*mPipeline, bindings, mPipeline->groupsX(n.x), mPipeline->groupsY(n.y),
               mPipeline->groupsZ(n.z));
}

}  // namespace sky
