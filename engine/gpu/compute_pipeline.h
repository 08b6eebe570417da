#pragma once
// A compute pipeline built from compiled SPIR-V. Its descriptor set layout (set 0) and push
// constant range come from the shader's own reflection, so C++ never restates bindings.
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include <filesystem>

#include "engine/shader/shader_compiler.h"
#include "engine/shader/spirv_reflect.h"

namespace sky {

class Context;

// Compiles `file` for `ctx`: `defines` and the device's own (Context::shaderDefines, driver
// workarounds), so every pipeline a pass builds for a device sees them.
CompiledShader compileForDevice(const Context& ctx, ShaderCompiler& compiler,
                                const std::filesystem::path& file,
                                std::vector<ShaderDefine> defines = {});

// Wall time (ms) this process has spent making compute pipelines, on every thread: compiling
// the shaders or loading them from the SPIR-V cache (compileForDevice), and creating the
// pipelines (lavapipe compiles to machine code there, or takes it from Mesa's cache). What a
// first frame pays before it can draw; the render report states it (docs/outputs.md).
double pipelineBuildMs();

class ComputePipeline;
// compileForDevice, then the pipeline: the whole of what a pass with one shader builds.
ComputePipeline buildComputePipeline(const Context& ctx, ShaderCompiler& compiler,
                                     const std::filesystem::path& file, const std::string& name,
                                     std::vector<ShaderDefine> defines = {});

class ComputePipeline {
public:
  // Creates module, set layout, pipeline layout and pipeline. `name` is for debug output.
  ComputePipeline(const Context& ctx, const std::string& name, const std::vector<uint32_t>& spirv,
                  const ShaderReflection& reflection);
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  const std::string& name() const { return mName; }
  VkPipeline pipeline() const { return mPipeline; }
  VkPipelineLayout layout() const { return mLayout; }
  VkDescriptorSetLayout setLayout() const { return mSetLayout; }
  const ShaderReflection& reflection() const { return mReflection; }
  // The binding reflected at `binding` in set 0, or nullptr.
  const DescriptorBinding* binding(uint32_t binding) const;
  // Workgroups needed to cover `size` invocations along each axis.
  uint32_t groupsX(uint32_t size) const {
    return (size + mReflection.localSize[0] - 1) / mReflection.localSize[0];
  }
  uint32_t groupsY(uint32_t size) const {
    return (size + mReflection.localSize[1] - 1) / mReflection.localSize[1];
  }
  uint32_t groupsZ(uint32_t size) const {
    return (size + mReflection.localSize[2] - 1) / mReflection.localSize[2];
  }

private:
  void destroy();

  const Context& mCtx;
  std::string mName;
  ShaderReflection mReflection;
  VkDescriptorSetLayout mSetLayout = VK_NULL_HANDLE;
  VkPipelineLayout mLayout = VK_NULL_HANDLE;
  VkPipeline mPipeline = VK_NULL_HANDLE;
};

// A pipeline compiled at once (its SPIR-V and the hash of its source are known: a cache key
// can name it) but created only when first used. For bake passes, whose output usually
// comes from a cache file: creating a pipeline is most of what it costs (lavapipe translates
// it to machine code), ~30-90 ms each at start-up for nothing.
class LazyComputePipeline {
public:
  LazyComputePipeline(const Context& ctx, CompiledShader shader, std::string name);
  const ComputePipeline& get() const;  // created on the first call
  uint64_t sourceHash() const { return mShader.sourceHash; }

private:
  const Context& mCtx;
  CompiledShader mShader;
  std::string mName;
  mutable std::unique_ptr<ComputePipeline> mPipeline;
};

// One shader compiled once per combination of defines it meets: each pipeline is built on
// first use and kept. A pass whose frames choose among many variants (what is on screen, the
// scene's fixed choices) pays a compile only for those a run needs.
class ComputePipelineVariants {
public:
  ComputePipelineVariants(const Context& ctx, ShaderCompiler& compiler, std::filesystem::path file,
                          std::string name);
  const ComputePipeline& get(const std::vector<ShaderDefine>& defines);

private:
  const Context& mCtx;
  ShaderCompiler& mCompiler;
  std::filesystem::path mFile;
  std::string mName;
  std::map<std::vector<std::pair<std::string, std::string>>, std::unique_ptr<ComputePipeline>>
      mPipelines;
};

}  // namespace sky
