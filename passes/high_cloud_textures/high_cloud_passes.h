#pragma once
// The graph passes behind HighCloudTextures (high_cloud_textures.h). Each writes an imported
// persistent image and is a side effect: nothing in the bake graphs reads its result.
#include <cstdint>

#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "shaders/common/high_cloud_bake_shared.h"

namespace sky {

class Context;
class Sampler;
class ShaderCompiler;
struct CompiledShader;

// Procedural coefficients and rank/shape for one band of rows (shaders/high_cloud_bake.comp).
class HighCloudBakePass {
public:
  static constexpr const char* kName = "high_cloud_bake";
  struct Inputs {
    ImageId coefficients;  // N x N rgba16f, written in rows [size.y, size.y + size.z)
    ImageId rankShape;     // N x N rgba16f, the same rows: R rank, G shape, BA 0
    ImageId coverMap;      // r16f, sampled with `sampler` (1x1 white when there is none)
    shared::HighCloudBakeParams params{};
  };
  struct Outputs {
    ImageId coefficients;
    ImageId rankShape;
  };
  // Compiles the shader (once). `sampler` (linear, repeat) must outlive the pass.
  HighCloudBakePass(const Context& ctx, ShaderCompiler& compiler, const Sampler& sampler);
  // For cache keys: the shader's preprocessed source with every include (CompiledShader).
  uint64_t sourceHash() const { return mPipeline.sourceHash(); }
  // One use's data, in the frame graph (FrameGraph::add).
  struct Data {
    Inputs inputs;
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  // Created at the first bake: most runs load the textures from their cache.
  LazyComputePipeline mPipeline;
  const Sampler& mSampler;
};

// Tangent-space normals from the coefficients' opacity (shaders/high_cloud_normals.comp), of
// the texture itself or, smoother, of one of its mip levels.
class HighCloudNormalsPass {
public:
  static constexpr const char* kName = "high_cloud_normals";
  struct Inputs {
    ImageId coefficients;     // N x N rgba16f
    ImageId levels;           // HighCloudLevelsPass's output (read only when level > 0)
    ImageId normals;          // N x N rgba16f, overwritten
    uint32_t size = 0;        // N
    uint32_t coarseSize = 0;  // C
    uint32_t level = 0;       // 0: the texture's own opacity; 1 .. log2(N / C) - 1: that level's
    // The height of opacity 1, in tiles (HIGH_CLOUD_NORMAL_RELIEF or _CIRRUS_NORMAL_RELIEF).
    float relief = float(HIGH_CLOUD_NORMAL_RELIEF);
  };
  struct Outputs {
    ImageId normals;
  };
  // `sampler` (any; the levels are read with texelFetch) must outlive the pass.
  HighCloudNormalsPass(const Context& ctx, ShaderCompiler& compiler, const Sampler& sampler);
  uint64_t sourceHash() const { return mSourceHash; }
  // One use's data, in the frame graph (FrameGraph::add).
  struct Data {
    Inputs inputs;
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  HighCloudNormalsPass(const Context& ctx, const CompiledShader& shader, const Sampler& sampler);
  ComputePipeline mPipeline;
  uint64_t mSourceHash = 0;
  const Sampler& mSampler;
};

// The coefficients' mip levels 1 .. log2(N / C) - 1 side by side in one image
// (shaders/high_cloud_levels.comp, common/high_cloud_levels.glsl), for the draw's filtering by
// footprint and the smoothed normals.
class HighCloudLevelsPass {
public:
  static constexpr const char* kName = "high_cloud_levels";
  struct Inputs {
    ImageId coefficients;     // N x N rgba16f
    ImageId levels;           // (N - 2C) x N/2 rgba16f, overwritten
    uint32_t size = 0;        // N
    uint32_t coarseSize = 0;  // C; N / C is 4 or more
  };
  struct Outputs {
    ImageId levels;
  };
  HighCloudLevelsPass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add).
  struct Data {
    Inputs inputs;
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  ComputePipeline mPipeline;
};

// The coarse, box-filtered coefficients (shaders/high_cloud_reduce.comp).
class HighCloudReducePass {
public:
  static constexpr const char* kName = "high_cloud_reduce";
  struct Inputs {
    ImageId coefficients;     // N x N rgba16f
    ImageId coarse;           // C x C rgba16f, overwritten
    uint32_t size = 0;        // N
    uint32_t coarseSize = 0;  // C; N must be a multiple of it
  };
  struct Outputs {
    ImageId coarse;
  };
  HighCloudReducePass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add).
  struct Data {
    Inputs inputs;
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  ComputePipeline mPipeline;
};

// The per-cover coarse texture from the rank/shape texture
// (shaders/high_cloud_cover_reduce.comp): layer k is the coarse coefficients at cover
// k / (HIGH_CLOUD_COVER_STEPS - 1).
class HighCloudCoverReducePass {
public:
  static constexpr const char* kName = "high_cloud_cover_reduce";
  struct Inputs {
    ImageId rankShape;        // N x N rgba16f
    ImageId coverCoarse;      // C x C x HIGH_CLOUD_COVER_STEPS rgba16f (3D), overwritten
    uint32_t size = 0;        // N
    uint32_t coarseSize = 0;  // C; N must be a multiple of it
    float rampWidth = 0.0f;   // the style's w
  };
  struct Outputs {
    ImageId coverCoarse;
  };
  HighCloudCoverReducePass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add).
  struct Data {
    Inputs inputs;
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  ComputePipeline mPipeline;
};

}  // namespace sky
