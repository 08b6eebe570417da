#include "passes/atmosphere_composite/atmosphere_composite.h"

#include "engine/shader/shader_compiler.h"

namespace sky {
namespace {

ComputePipeline buildPipeline(const Context& ctx, ShaderCompiler& compiler) {
  CompiledShader shader = compileForDevice(ctx, compiler, "atmosphere_composite.comp");
  return ComputePipeline(ctx, AtmosphereCompositePass::kName, shader.spirv, shader.reflection);
}

}  // namespace

AtmosphereCompositePass::AtmosphereCompositePass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline(buildPipeline(ctx, compiler)) {}

AtmosphereCompositePass::Outputs AtmosphereCompositePass::setup(GraphBuilder& b, const Inputs& in) {
  mInputs = in;
  mInputs.params.layers.x = in.clouds ? 1u : 0u;
  b.read(in.starFlux, Access::StorageReadCompute);
  if (in.clouds) b.read(*in.clouds, Access::StorageReadCompute);
  b.read(in.sky, Access::StorageReadCompute);
  b.read(in.highClouds, Access::StorageReadCompute);
  ImageDesc desc;
  desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  desc.width = in.params.view.size.x;
  desc.height = in.params.view.size.y;
  desc.name = "beauty";
  mOutputs.beauty = b.write(b.create(desc), Access::StorageWriteCompute);
  return mOutputs;
}

void AtmosphereCompositePass::execute(PassContext& ctx) const {
  const auto& size = mInputs.params.view.size;
  ctx.dispatch(mPipeline,
               {Binding::of(ATMOSPHERE_COMPOSITE_BINDING_PARAMS, ctx.uniform(mInputs.params)),
                Binding::of(ATMOSPHERE_COMPOSITE_BINDING_BEAUTY, mOutputs.beauty),
                Binding::of(ATMOSPHERE_COMPOSITE_BINDING_SKY, mInputs.sky),
                Binding::of(ATMOSPHERE_COMPOSITE_BINDING_HIGH_CLOUDS, mInputs.highClouds),
                Binding::of(ATMOSPHERE_COMPOSITE_BINDING_LIGHTING, ctx.uniform(mInputs.lighting)),
                Binding::of(ATMOSPHERE_COMPOSITE_BINDING_STARS, mInputs.starFlux),
                // Without volumetric clouds the slot holds the high clouds, unread (layers.x 0):
                // a binding must name some image.
                Binding::of(ATMOSPHERE_COMPOSITE_BINDING_CLOUDS,
                            mInputs.clouds.value_or(mInputs.highClouds))},
               mPipeline.groupsX(size.x), mPipeline.groupsY(size.y));
}

}  // namespace sky
