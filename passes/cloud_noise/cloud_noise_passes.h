#pragma once
// The bake passes behind CloudNoise (cloud_noise.h): one compute shader each, writing a whole
// imported persistent texture. Each is a side effect: nothing in the bake graph reads its
// result but the read-back.
#include <cstdint>
#include <string>

#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "shaders/common/cloud_noise_shared.h"

namespace sky {

class Context;
class PassContext;
class ShaderCompiler;
struct CompiledShader;

// shaders/<name>.comp over an N^3 volume (cloud_noise_volume) or an N^2 texture
// (cloud_noise_curl), N = params.size.x.
class CloudNoiseBakePass {
public:
  struct Inputs {
    ImageId target;  // rgba8, N^3 (3D) or N^2 (2D), overwritten whole
    shared::CloudNoiseParams params{};
    const char* label = nullptr;  // the use's name in graphs and timings; nullptr: name()
  };
  struct Outputs {
    ImageId target;
  };
  // Compiles shaders/<name>.comp (once; the pipeline is created at the first bake, as most
  // runs load the noise from its cache); `name` also names the pass in graphs and timings.
  CloudNoiseBakePass(const Context& ctx, ShaderCompiler& compiler, const std::string& name);
  const std::string& name() const { return mName; }
  // For cache keys: the shader's preprocessed source with every include (CompiledShader).
  uint64_t sourceHash() const { return mPipeline.sourceHash(); }
  // Adds one use of the pass to `graph`. Unlike setup() of single-use passes, every use keeps
  // its own inputs, so one object can bake the shape and the detail volume in the same graph.
  Outputs addTo(FrameGraph& graph, const Inputs& inputs) const;

private:
  void execute(PassContext& ctx, const Inputs& inputs) const;

  std::string mName;
  LazyComputePipeline mPipeline;
};

}  // namespace sky
