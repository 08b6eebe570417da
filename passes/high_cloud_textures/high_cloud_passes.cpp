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

HighCloudBakePass::Outputs HighCloudBakePass::setup(GraphBuilder& b, const Inputs& in) {
  const auto& size = in.params.size;
  if (size.x == 0 || size.z == 0 || size.y + size.z > size.x)
    internalError("high_cloud_bake: band of rows " + std::to_string(size.y) + "+" +
                  std::to_string(size.z) + " outside a " + std::to_string(size.x) + " texture");
  (void)mPipeline.get();  // created now, before the graph records
  mInputs = in;
  mInputs.coverMap = b.read(in.coverMap, Access::SampledCompute);
  // A band writes only its rows; the others keep what earlier bands wrote, which the graph
  // preserves because imported images keep their layout between graphs.
  mOutputs.coefficients = b.write(in.coefficients, Access::StorageWriteCompute);
  mOutputs.rankShape = b.write(in.rankShape, Access::StorageWriteCompute);
  b.sideEffect();
  return mOutputs;
}

void HighCloudBakePass::execute(PassContext& ctx) const {
  const auto& size = mInputs.params.size;
  const ComputePipeline& pipeline = mPipeline.get();
  ctx.dispatch(pipeline,
               {Binding::of(HIGH_CLOUD_BAKE_BINDING_PARAMS, ctx.uniform(mInputs.params)),
                Binding::of(HIGH_CLOUD_BAKE_BINDING_COVER_MAP, mInputs.coverMap, &mSampler),
                Binding::of(HIGH_CLOUD_BAKE_BINDING_COEFFICIENTS, mOutputs.coefficients),
                Binding::of(HIGH_CLOUD_BAKE_BINDING_RANK_SHAPE, mOutputs.rankShape)},
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

HighCloudNormalsPass::Outputs HighCloudNormalsPass::setup(GraphBuilder& b, const Inputs& in) {
  if (in.size == 0) internalError("high_cloud_normals: empty texture");
  if (in.level > 0 && (in.coarseSize == 0 || (in.size / in.coarseSize) >> in.level <= 1))
    internalError("high_cloud_normals: no level " + std::to_string(in.level) + " between " +
                  std::to_string(in.size) + " and " + std::to_string(in.coarseSize));
  mInputs = in;
  mInputs.coefficients = b.read(in.coefficients, Access::StorageReadCompute);
  mInputs.levels = b.read(in.levels, Access::SampledCompute);
  mOutputs.normals = b.write(in.normals, Access::StorageWriteCompute);
  b.sideEffect();
  return mOutputs;
}

void HighCloudNormalsPass::execute(PassContext& ctx) const {
  shared::HighCloudNormalsParams push{};
  push.size = glm::uvec4(mInputs.size, mInputs.level, mInputs.coarseSize, 0);
  // The relief in texels, so the normals describe the same surface at every resolution.
  push.relief = glm::vec4(mInputs.relief * float(mInputs.size), 0, 0, 0);
  ctx.dispatch(mPipeline,
               {Binding::of(HIGH_CLOUD_NORMALS_BINDING_COEFFICIENTS, mInputs.coefficients),
                Binding::of(HIGH_CLOUD_NORMALS_BINDING_LEVELS, mInputs.levels, &mSampler),
                Binding::of(HIGH_CLOUD_NORMALS_BINDING_NORMALS, mOutputs.normals)},
               mPipeline.groupsX(mInputs.size), mPipeline.groupsY(mInputs.size), 1, &push,
               sizeof push);
}

HighCloudLevelsPass::HighCloudLevelsPass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline([&] {
        CompiledShader shader = compileForDevice(ctx, compiler, std::string(kName) + ".comp");
        return ComputePipeline(ctx, kName, shader.spirv, shader.reflection);
      }()) {}

HighCloudLevelsPass::Outputs HighCloudLevelsPass::setup(GraphBuilder& b, const Inputs& in) {
  if (in.coarseSize == 0 || in.size < 4 * in.coarseSize || in.size % in.coarseSize != 0)
    internalError("high_cloud_levels: " + std::to_string(in.size) + " is not 4 or more times " +
                  std::to_string(in.coarseSize));
  mInputs = in;
  mInputs.coefficients = b.read(in.coefficients, Access::StorageReadCompute);
  mOutputs.levels = b.write(in.levels, Access::StorageWriteCompute);
  b.sideEffect();
  return mOutputs;
}

void HighCloudLevelsPass::execute(PassContext& ctx) const {
  shared::HighCloudLevelsParams push{};
  push.size = glm::uvec4(mInputs.size, mInputs.coarseSize, 0, 0);
  const uint32_t width = mInputs.size - 2 * mInputs.coarseSize, height = mInputs.size / 2;
  ctx.dispatch(mPipeline,
               {Binding::of(HIGH_CLOUD_LEVELS_BINDING_COEFFICIENTS, mInputs.coefficients),
                Binding::of(HIGH_CLOUD_LEVELS_BINDING_LEVELS, mOutputs.levels)},
               mPipeline.groupsX(width), mPipeline.groupsY(height), 1, &push, sizeof push);
}

HighCloudReducePass::HighCloudReducePass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline([&] {
        CompiledShader shader = compileForDevice(ctx, compiler, std::string(kName) + ".comp");
        return ComputePipeline(ctx, kName, shader.spirv, shader.reflection);
      }()) {}

HighCloudReducePass::Outputs HighCloudReducePass::setup(GraphBuilder& b, const Inputs& in) {
  if (in.coarseSize == 0 || in.size < in.coarseSize || in.size % in.coarseSize != 0)
    internalError("high_cloud_reduce: " + std::to_string(in.size) + " is not a multiple of " +
                  std::to_string(in.coarseSize));
  mInputs = in;
  mInputs.coefficients = b.read(in.coefficients, Access::StorageReadCompute);
  mOutputs.coarse = b.write(in.coarse, Access::StorageWriteCompute);
  b.sideEffect();
  return mOutputs;
}

void HighCloudReducePass::execute(PassContext& ctx) const {
  shared::HighCloudReduceParams push{};
  push.size = glm::uvec4(mInputs.size, mInputs.coarseSize, mInputs.size / mInputs.coarseSize, 0);
  ctx.dispatch(mPipeline,
               {Binding::of(HIGH_CLOUD_REDUCE_BINDING_COEFFICIENTS, mInputs.coefficients),
                Binding::of(HIGH_CLOUD_REDUCE_BINDING_COARSE, mOutputs.coarse)},
               mPipeline.groupsX(mInputs.coarseSize), mPipeline.groupsY(mInputs.coarseSize), 1,
               &push, sizeof push);
}

HighCloudCoverReducePass::HighCloudCoverReducePass(const Context& ctx, ShaderCompiler& compiler)
    : mPipeline([&] {
        CompiledShader shader = compileForDevice(ctx, compiler, std::string(kName) + ".comp");
        return ComputePipeline(ctx, kName, shader.spirv, shader.reflection);
      }()) {}

HighCloudCoverReducePass::Outputs HighCloudCoverReducePass::setup(GraphBuilder& b,
                                                                  const Inputs& in) {
  if (in.coarseSize == 0 || in.size < in.coarseSize || in.size % in.coarseSize != 0)
    internalError("high_cloud_cover_reduce: " + std::to_string(in.size) + " is not a multiple of " +
                  std::to_string(in.coarseSize));
  mInputs = in;
  mInputs.rankShape = b.read(in.rankShape, Access::StorageReadCompute);
  mOutputs.coverCoarse = b.write(in.coverCoarse, Access::StorageWriteCompute);
  b.sideEffect();
  return mOutputs;
}

void HighCloudCoverReducePass::execute(PassContext& ctx) const {
  shared::HighCloudCoverReduceParams push{};
  push.size = glm::uvec4(mInputs.size, mInputs.coarseSize, mInputs.size / mInputs.coarseSize,
                         HIGH_CLOUD_COVER_STEPS);
  push.ramp = glm::vec4(mInputs.rampWidth, 0.0f, 0.0f, 0.0f);
  ctx.dispatch(mPipeline,
               {Binding::of(HIGH_CLOUD_COVER_REDUCE_BINDING_RANK_SHAPE, mInputs.rankShape),
                Binding::of(HIGH_CLOUD_COVER_REDUCE_BINDING_COARSE, mOutputs.coverCoarse)},
               mPipeline.groupsX(mInputs.coarseSize), mPipeline.groupsY(mInputs.coarseSize),
               mPipeline.groupsZ(HIGH_CLOUD_COVER_STEPS), &push, sizeof push);
}

}  // namespace sky
