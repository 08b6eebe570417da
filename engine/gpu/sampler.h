#pragma once
// An immutable sampler. Linear filtering; wrap mode per use (noise tiles, LUTs clamp).
#include <vulkan/vulkan.h>

namespace sky {

class Context;

enum class SamplerWrap : uint8_t { Clamp, Repeat };

class Sampler {
public:
  Sampler(const Context& ctx, SamplerWrap wrap, bool linear = true);
  ~Sampler();
  Sampler(const Sampler&) = delete;
  Sampler& operator=(const Sampler&) = delete;
  VkSampler sampler() const { return mSampler; }

private:
  const Context& mCtx;
  VkSampler mSampler = VK_NULL_HANDLE;
};

}  // namespace sky
