#include "passes/volumetric_clouds/volumetric_clouds.h"

#include <algorithm>

#include "engine/core/error.h"
#include "engine/gpu/sampler.h"

namespace sky {

VolumetricCloudsPass::VolumetricCloudsPass(const Context& ctx, ShaderCompiler& compiler)
    : mPipelines(ctx, compiler, "volumetric_clouds.comp", kName) {}

VolumetricCloudsPass::Outputs VolumetricCloudsPass::setup(GraphBuilder& b, const Inputs& in,
                                                          Data& d) {
  d.inputs = in;
  if (in.hostDepth) {
    if (!in.hostDepth->sampler) internalError("volumetric_clouds: no host depth sampler");
    if (in.params.marchBlock > 1)
      internalError("volumetric_clouds: a host's depth with temporal reuse's sparse march");
    b.read(in.hostDepth->depth, Access::SampledCompute);
  }
  d.pipeline = in.hostDepth ? &mPipelines.get(in.variant, {{"VOLUMETRIC_CLOUDS_HOST_DEPTH", "1"}})
                            : &mPipelines.get(in.variant);
  readCloudTextures(b, in.textures);
  b.read(in.ambient, Access::StorageReadCompute);
  if (in.variant.light == CloudLight::Volume) {
    if (!in.lightVolumeSampler) internalError("volumetric_clouds: no light volume sampler");
    b.read(in.lightVolume, Access::SampledCompute);
  }
  // With temporal reuse the pass marches one pixel of every marchBlock x marchBlock square.
  const uint32_t block = std::max(in.params.marchBlock, 1u);
  ImageDesc desc;
  desc.width = (in.params.view.size.x + block - 1) / block;
  desc.height = (in.params.view.size.y + block - 1) / block;
  const CloudImages images = writeCloudImages(
      b, desc.width, desc.height,
      {"clouds", "the marched clouds: premultiplied radiance (RGB) and opacity (A)",
       "clouds_depth",
       "the clouds' transmittance-weighted distance (m, R) and where the ray enters the shells "
       "(m, G)"});
  d.outputs.clouds = images.clouds;
  d.outputs.depth = images.depth;
  desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  desc.name = "cloud_steps";
  desc.about =
      "density samples per pixel along the view ray (R) and in the light marches (G): "
      "the raymarch's cost";
  desc.view = DebugView::Heat;
  desc.channels = "view,light";
  d.outputs.steps = b.write(b.create(desc), Access::StorageWriteCompute);
  return d.outputs;
}

void VolumetricCloudsPass::execute(PassContext& ctx, const Data& d) const {
  const ImageDesc& size = ctx.image(d.outputs.clouds).desc();
  std::vector<Binding> bindings = cloudTextureBindings(d.inputs.textures);
  bindings.insert(bindings.end(),
                  {Binding::of(VOLUMETRIC_CLOUDS_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
                   Binding::of(VOLUMETRIC_CLOUDS_BINDING_LIGHTING, ctx.uniform(d.inputs.lighting)),
                   Binding::of(VOLUMETRIC_CLOUDS_BINDING_AMBIENT, d.inputs.ambient),
                   Binding::of(VOLUMETRIC_CLOUDS_BINDING_CLOUDS, d.outputs.clouds),
                   Binding::of(VOLUMETRIC_CLOUDS_BINDING_DEPTH, d.outputs.depth),
                   Binding::of(VOLUMETRIC_CLOUDS_BINDING_STEPS, d.outputs.steps)});
  if (d.inputs.variant.light == CloudLight::Volume)
    bindings.push_back(Binding::of(CLOUD_LIGHT_VOLUME_BINDING_IMAGE, d.inputs.lightVolume,
                                   d.inputs.lightVolumeSampler));
  if (const auto& host = d.inputs.hostDepth) {
    bindings.push_back(
        Binding::of(VOLUMETRIC_CLOUDS_BINDING_HOST_DEPTH, host->depth, host->sampler));
    bindings.push_back(
        Binding::of(VOLUMETRIC_CLOUDS_BINDING_HOST_DEPTH_PARAMS, ctx.uniform(host->mapping)));
  }
  ctx.dispatch(*d.pipeline, bindings, d.pipeline->groupsX(size.width),
               d.pipeline->groupsY(size.height));
}

}  // namespace sky
