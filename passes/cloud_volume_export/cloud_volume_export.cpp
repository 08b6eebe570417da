#include "passes/cloud_volume_export/cloud_volume_export.h"

#include "engine/core/error.h"
#include "engine/gpu/sampler.h"

namespace sky {

CloudVolumeExportPass::CloudVolumeExportPass(const Context& ctx, ShaderCompiler& compiler)
    : mPipelines(ctx, compiler, "cloud_volume_export.comp", kName) {}

CloudVolumeExportPass::Outputs CloudVolumeExportPass::setup(GraphBuilder& b, const Inputs& in) {
  const CloudTextures& t = in.textures;
  if (!t.noiseSampler || !t.weatherSampler) internalError("cloud volume export: no sampler");
  mInputs = in;
  mPipeline = &mPipelines.get(in.params);
  for (ImageId id : {t.shape, t.detail, t.curl, t.weather, t.weatherCoarse})
    b.read(id, Access::SampledCompute);
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
  const CloudTextures& t = mInputs.textures;
  const glm::uvec4& n = mInputs.box.voxels;
  ctx.dispatch(
      *mPipeline,
      {Binding::of(VOLUMETRIC_CLOUDS_BINDING_PARAMS, ctx.uniform(mInputs.params)),
       Binding::of(CLOUD_VOLUME_EXPORT_BINDING_PARAMS, ctx.uniform(mInputs.box)),
       Binding::of(CLOUD_VOLUME_EXPORT_BINDING_GRID, mOutputs.grid),
       Binding::of(VOLUMETRIC_CLOUDS_BINDING_SHAPE, t.shape, t.noiseSampler),
       Binding::of(VOLUMETRIC_CLOUDS_BINDING_DETAIL, t.detail, t.noiseSampler),
       Binding::of(VOLUMETRIC_CLOUDS_BINDING_CURL, t.curl, t.noiseSampler),
       Binding::of(VOLUMETRIC_CLOUDS_BINDING_WEATHER, t.weather, t.weatherSampler),
       Binding::of(VOLUMETRIC_CLOUDS_BINDING_WEATHER_COARSE, t.weatherCoarse, t.weatherSampler)},
      mPipeline->groupsX(n.x), mPipeline->groupsY(n.y), mPipeline->groupsZ(n.z));
}

}  // namespace sky
