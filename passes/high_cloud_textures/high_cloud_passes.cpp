#include "passes/high_cloud_textures/high_cloud_passes.h"

#include <string>

#include "engine/core/error.h"
#include "engine/gpu/sampler.h"
#include "engine/shader/shader_compiler.h"

namespace sky {

HighCloudBakePass::HighCloudBakePass(const Context& ctx, ShaderCompiler& compiler,
                                     const Sampler& sampler)
    : mPipeline(ctx, compileForDevice(ctx, compiler, std::string(kName) + ".comp"), kName),
      mSampler(sampler) {}

HighCloudBakePass::Outputs HighCloudBakePass::setup(GraphBuilder& b, const Inputs& in, Data& d) {
  const auto& size = in.params.size;
  if (size.x == 0 || size.z == 0 || size.y + size.z > size.x)
    internalError("high_cloud_bake: band of rows " + std::to_string(size.y) + "+" +
                  std::to_string(size.z) + " outside a " + std::to_string(size.x) + " texture");
  (void)mPipeline.get();  // created now, before the graph records
  d.inputs = in;
  d.inputs.coverMap = b.read(in.coverMap, Access::SampledCompute);
  // A band writes only its rows; the others keep what earlier bands wrote, which the graph
  // preserves because imported images keep their layout between graphs.
  d.outputs.coefficients = b.write(in.coefficients, Access::StorageWriteCompute);
  d.outputs.rankShape = b.write(in.rankShape, Access::StorageWriteCompute);
  b.sideEffect();
  return d.outputs;
}

void HighCloudBakePass::execute(PassContext& ctx, const Data& d) const {
  const auto& size = d.inputs.params.size;
  const ComputePipeline& pipeline = mPipeline.get();
  ctx.dispatch(pipeline,
               {Binding::of(HIGH_CLOUD_BAKE_BINDING_PARAMS, ctx.uniform(d.inputs.params)),
                Binding::of(HIGH_CLOUD_BAKE_BINDING_COVER_MAP, d.inputs.coverMap, &mSampler),
                Binding::of(HIGH_CLOUD_BAKE_BINDING_COEFFICIENTS, d.outputs.coefficients),
                Binding::of(HIGH_CLOUD_BAKE_BINDING_RANK_SHAPE, d.outputs.rankShape)},
               pipeline.groupsX(size.x), pipeline.groupsY(size.z));
}

HighCloudNormalsPass::HighCloudNormalsPass(const Context& ctx, ShaderCompiler& compiler,
                                           const Sampler& sampler)
    : HighCloudNormalsPass(ctx, compileForDevice(ctx, compiler, std::string(kName) + ".comp"),
                           sampler) {}

HighCloudNormalsPass::HighCloudNormalsPass(const Context& ctx, const CompiledShader& shader,
                                           const Sampler& sampler)
    : mPipeline(ctx, kName, shader.spirv, shader.reflection),
      mSourceHash(shader.sourceHash),
      mSampler(sampler) {}

HighCloudNormalsPass::Outputs HighCloudNormalsPass::setup(GraphBuilder& b, const Inputs& in,
                                                          Data& d) {
  if (in.size == 0) internalError("high_cloud_normals: empty texture");
  if (in.level > 0 && (in.coarseSize == 0 || (in.size / in.coarseSize) >> in.level <= 1))
    internalError("high_cloud_normals: no level " + std::to_string(in.level) + " between " +
                  std::to_string(in.size) + " and " + std::to_string(in.coarseSize));
  d.inputs = in;
  d.inputs.coefficients = b.read(in.coefficients, Access::StorageReadCompute);
  d.inputs.levels = b.read(in.levels, Access::SampledCompute);
  d.outputs.normals = b.write(in.normals, Access::StorageWriteCompute);
  b.sideEffect();
  return d.outputs;
}

void HighCloudNormalsPass::execute(PassContext& ctx, const Data& d) const {
  shared::HighCloudNormalsParams push{};
  push.size = glm::uvec4(d.inputs.size, d.inputs.level, d.inputs.coarseSize, 0);
  // The relief in texels, so the normals describe the same surface at every resolution.
  push.relief = glm::vec4(d.inputs.relief * float(d.inputs.size), 0, 0, 0);
  ctx.dispatch(mPipeline,
               {Binding::of(HIGH_CLOUD_NORMALS_BINDING_COEFFICIENTS, d.inputs.coefficients),
                Binding::of(HIGH_CLOUD_NORMALS_BINDING_LEVELS, d.inputs.levels, &mSampler),
                Binding::of(HIGH_CLOUD_NORMALS_BINDING_NORMALS, d.outputs.normals)},
               mPipeline.groupsX(d.inputs.size), mPipeline.groupsY(d.inputs.size), 1, &push,
               sizeof push);
}

HighCloudLevelsPass::HighCloudLevelsPass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline([&] {
        CompiledShader shader = compileForDevice(ctx, compiler, std::string(kName) + ".comp");
        return ComputePipeline(ctx, kName, shader.spirv, shader.reflection);
      }()) {}

HighCloudLevelsPass::Outputs HighCloudLevelsPass::setup(GraphBuilder& b, const Inputs& in,
                                                        Data& d) {
  if (in.coarseSize == 0 || in.size < 4 * in.coarseSize || in.size % in.coarseSize != 0)
    internalError("high_cloud_levels: " + std::to_string(in.size) + " is not 4 or more times " +
                  std::to_string(in.coarseSize));
  d.inputs = in;
  d.inputs.coefficients = b.read(in.coefficients, Access::StorageReadCompute);
  d.outputs.levels = b.write(in.levels, Access::StorageWriteCompute);
  b.sideEffect();
  return d.outputs;
}

void HighCloudLevelsPass::execute(PassContext& ctx, const Data& d) const {
  shared::HighCloudLevelsParams push{};
  push.size = glm::uvec4(d.inputs.size, d.inputs.coarseSize, 0, 0);
  const uint32_t width = d.inputs.size - 2 * d.inputs.coarseSize, height = d.inputs.size / 2;
  ctx.dispatch(mPipeline,
               {Binding::of(HIGH_CLOUD_LEVELS_BINDING_COEFFICIENTS, d.inputs.coefficients),
                Binding::of(HIGH_CLOUD_LEVELS_BINDING_LEVELS, d.outputs.levels)},
               mPipeline.groupsX(width), mPipeline.groupsY(height), 1, &push, sizeof push);
}

HighCloudReducePass::HighCloudReducePass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline([&] {
        CompiledShader shader = compileForDevice(ctx, compiler, std::string(kName) + ".comp");
        return ComputePipeline(ctx, kName, shader.spirv, shader.reflection);
      }()) {}

HighCloudReducePass::Outputs HighCloudReducePass::setup(GraphBuilder& b, const Inputs& in,
                                                        Data& d) {
  if (in.coarseSize == 0 || in.size < in.coarseSize || in.size % in.coarseSize != 0)
    internalError("high_cloud_reduce: " + std::to_string(in.size) + " is not a multiple of " +
                  std::to_string(in.coarseSize));
  d.inputs = in;
  d.inputs.coefficients = b.read(in.coefficients, Access::StorageReadCompute);
  d.outputs.coarse = b.write(in.coarse, Access::StorageWriteCompute);
  b.sideEffect();
  return d.outputs;
}

void HighCloudReducePass::execute(PassContext& ctx, const Data& d) const {
  shared::HighCloudReduceParams push{};
  push.size =
      glm::uvec4(d.inputs.size, d.inputs.coarseSize, d.inputs.size / d.inputs.coarseSize, 0);
  ctx.dispatch(mPipeline,
               {Binding::of(HIGH_CLOUD_REDUCE_BINDING_COEFFICIENTS, d.inputs.coefficients),
                Binding::of(HIGH_CLOUD_REDUCE_BINDING_COARSE, d.outputs.coarse)},
               mPipeline.groupsX(d.inputs.coarseSize), mPipeline.groupsY(d.inputs.coarseSize), 1,
               &push, sizeof push);
}

HighCloudCoverReducePass::HighCloudCoverReducePass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline([&] {
        CompiledShader shader = compileForDevice(ctx, compiler, std::string(kName) + ".comp");
        return ComputePipeline(ctx, kName, shader.spirv, shader.reflection);
      }()) {}

HighCloudCoverReducePass::Outputs HighCloudCoverReducePass::setup(GraphBuilder& b, const Inputs& in,
                                                                  Data& d) {
  if (in.coarseSize == 0 || in.size < in.coarseSize || in.size % in.coarseSize != 0)
    internalError("high_cloud_cover_reduce: " + std::to_string(in.size) + " is not a multiple of " +
                  std::to_string(in.coarseSize));
  d.inputs = in;
  d.inputs.rankShape = b.read(in.rankShape, Access::StorageReadCompute);
  d.outputs.coverCoarse = b.write(in.coverCoarse, Access::StorageWriteCompute);
  b.sideEffect();
  return d.outputs;
}

void HighCloudCoverReducePass::execute(PassContext& ctx, const Data& d) const {
  shared::HighCloudCoverReduceParams push{};
  push.size = glm::uvec4(d.inputs.size, d.inputs.coarseSize, d.inputs.size / d.inputs.coarseSize,
                         HIGH_CLOUD_COVER_STEPS);
  push.ramp = glm::vec4(d.inputs.rampWidth, 0.0f, 0.0f, 0.0f);
  ctx.dispatch(mPipeline,
               {Binding::of(HIGH_CLOUD_COVER_REDUCE_BINDING_RANK_SHAPE, d.inputs.rankShape),
                Binding::of(HIGH_CLOUD_COVER_REDUCE_BINDING_COARSE, d.outputs.coverCoarse)},
               mPipeline.groupsX(d.inputs.coarseSize), mPipeline.groupsY(d.inputs.coarseSize),
               mPipeline.groupsZ(HIGH_CLOUD_COVER_STEPS), &push, sizeof push);
}

}  // namespace sky
