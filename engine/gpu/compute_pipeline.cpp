#include "engine/gpu/compute_pipeline.h"

#include <atomic>
#include <chrono>

#include "engine/gpu/context.h"
#include "engine/gpu/vk_check.h"

namespace sky {
namespace {

std::atomic<int64_t> gBuildNs{0};

// Adds the time from its construction to its end to pipelineBuildMs().
class BuildClock {
public:
  ~BuildClock() {
    gBuildNs += std::chrono::duration_cast<std::chrono::nanoseconds>(
                    std::chrono::steady_clock::now() - mStart)
                    .count();
  }

private:
  std::chrono::steady_clock::time_point mStart = std::chrono::steady_clock::now();
};

}  // namespace

double pipelineBuildMs() {
  return static_cast<double>(gBuildNs.load()) * 1e-6;
}

CompiledShader compileForDevice(const Context& ctx, ShaderCompiler& compiler,
                                const std::filesystem::path& file,
                                std::vector<ShaderDefine> defines) {
  BuildClock clock;
  for (const auto& [name, value] : ctx.shaderDefines()) defines.push_back({name, value});
  return compiler.compile(file, defines);
}

ComputePipeline buildComputePipeline(const Context& ctx, ShaderCompiler& compiler,
                                     const std::filesystem::path& file, const std::string& name,
                                     std::vector<ShaderDefine> defines) {
  CompiledShader shader = compileForDevice(ctx, compiler, file, std::move(defines));
  return ComputePipeline(ctx, name, shader.spirv, shader.reflection);
}

LazyComputePipeline::LazyComputePipeline(const Context& ctx, CompiledShader shader,
                                         std::string name)
    : mCtx(ctx), mShader(std::move(shader)), mName(std::move(name)) {}

const ComputePipeline& LazyComputePipeline::get() const {
  if (!mPipeline)
    mPipeline = std::make_unique<ComputePipeline>(mCtx, mName, mShader.spirv, mShader.reflection);
  return *mPipeline;
}

ComputePipelineVariants::ComputePipelineVariants(const Context& ctx, ShaderCompiler& compiler,
                                                 std::filesystem::path file, std::string name)
    : mCtx(ctx), mCompiler(compiler), mFile(std::move(file)), mName(std::move(name)) {}

const ComputePipeline& ComputePipelineVariants::get(const std::vector<ShaderDefine>& defines) {
  std::vector<std::pair<std::string, std::string>> key;
  for (const ShaderDefine& d : defines) key.emplace_back(d.name, d.value);
  std::unique_ptr<ComputePipeline>& pipeline = mPipelines[key];
  if (!pipeline) {
    CompiledShader shader = compileForDevice(mCtx, mCompiler, mFile, defines);
    pipeline = std::make_unique<ComputePipeline>(mCtx, mName, shader.spirv, shader.reflection);
  }
  return *pipeline;
}

ComputePipeline::ComputePipeline(const Context& ctx, const std::string& name,
                                 const std::vector<uint32_t>& spirv,
                                 const ShaderReflection& reflection)
    : mCtx(ctx), mName(name), mReflection(reflection) {
  BuildClock clock;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (const DescriptorBinding& b : reflection.bindings) {
    // One set per pass keeps binding numbers meaningful in the shared headers.
    if (b.set != 0)
      internalError(name + ": binding '" + b.name + "' uses descriptor set " +
                    std::to_string(b.set) + "; passes use set 0 only");
    bindings.push_back({b.binding, b.type, b.count, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  }
  VkDevice d = ctx.device();
  VkShaderModule module = VK_NULL_HANDLE;
  try {
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.bindingCount = static_cast<uint32_t>(bindings.size());
    setInfo.pBindings = bindings.data();
    SKY_VK(vkCreateDescriptorSetLayout(d, &setInfo, nullptr, &mSetLayout));

    VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, reflection.pushConstantSize};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &mSetLayout;
    layoutInfo.pushConstantRangeCount = reflection.pushConstantSize ? 1 : 0;
    layoutInfo.pPushConstantRanges = &push;
    SKY_VK(vkCreatePipelineLayout(d, &layoutInfo, nullptr, &mLayout));

    VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = spirv.size() * sizeof(uint32_t);
    moduleInfo.pCode = spirv.data();
    SKY_VK(vkCreateShaderModule(d, &moduleInfo, nullptr, &module));

    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.layout = mLayout;
    SKY_VK(vkCreateComputePipelines(d, VK_NULL_HANDLE, 1, &info, nullptr, &mPipeline));
    ctx.setName(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(mPipeline), name);
  } catch (...) {
    if (module) vkDestroyShaderModule(d, module, nullptr);
    destroy();
    throw;
  }
  vkDestroyShaderModule(d, module, nullptr);
}

ComputePipeline::~ComputePipeline() {
  destroy();
}

void ComputePipeline::destroy() {
  VkDevice d = mCtx.device();
  if (mPipeline) vkDestroyPipeline(d, mPipeline, nullptr);
  if (mLayout) vkDestroyPipelineLayout(d, mLayout, nullptr);
  if (mSetLayout) vkDestroyDescriptorSetLayout(d, mSetLayout, nullptr);
  mPipeline = VK_NULL_HANDLE;
  mLayout = VK_NULL_HANDLE;
  mSetLayout = VK_NULL_HANDLE;
}

const DescriptorBinding* ComputePipeline::binding(uint32_t index) const {
  for (const auto& b : mReflection.bindings)
    if (b.set == 0 && b.binding == index) return &b;
  return nullptr;
}

}  // namespace sky
