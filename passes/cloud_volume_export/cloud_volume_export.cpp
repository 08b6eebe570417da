#include "passes/cloud_volume_export/cloud_volume_export.h"

namespace sky {

CloudVolumeExportPass::CloudVolumeExportPass(const Context& ctx, ShaderCompiler& compiler)
    : mPipelines(ctx, compiler, "cloud_volume_export.comp", kName) {}

CloudVolumeExportPass::Outputs CloudVolumeExportPass::setup(GraphBuilder& b, const Inputs& in,
                                                            Data& d) {
  d.inputs = in;
  d.pipeline = &mPipelines.get(in.variant);
  readCloudTextures(b, in.textures);
  ImageDesc desc;
  desc.dim = ImageDim::Tex3D;
  desc.width = in.box.voxels.x;
  desc.height = in.box.voxels.y;
  desc.depth = in.box.voxels.z;
  desc.format = VK_FORMAT_R32_SFLOAT;
  desc.name = "cloud_volume";
  d.outputs.grid = b.write(b.create(desc), Access::StorageWriteCompute);
  return d.outputs;
}

void CloudVolumeExportPass::execute(PassContext& ctx, const Data& d) const {
  const glm::uvec4& n = d.inputs.box.voxels;
  std::vector<Binding> bindings = cloudTextureBindings(d.inputs.textures);
  bindings.insert(bindings.end(),
                  {Binding::of(VOLUMETRIC_CLOUDS_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
                   Binding::of(CLOUD_VOLUME_EXPORT_BINDING_PARAMS, ctx.uniform(d.inputs.box)),
                   Binding::of(CLOUD_VOLUME_EXPORT_BINDING_GRID, d.outputs.grid)});
  ctx.dispatch(*d.pipeline, bindings, d.pipeline->groupsX(n.x), d.pipeline->groupsY(n.y),
               d.pipeline->groupsZ(n.z));
}

}  // namespace sky
