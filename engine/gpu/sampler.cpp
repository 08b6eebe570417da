#include "engine/gpu/sampler.h"

#include "engine/gpu/context.h"
#include "engine/gpu/vk_check.h"

namespace sky {

Sampler::Sampler(const Context& ctx, SamplerWrap wrap, bool linear) : mCtx(ctx) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  VkSamplerAddressMode mode = wrap == SamplerWrap::Repeat ? VK_SAMPLER_ADDRESS_MODE_REPEAT
                                                          : VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeU = info.addressModeV = info.addressModeW = mode;
  info.maxLod = 0.0f;
  SKY_VK(vkCreateSampler(ctx.device(), &info, nullptr, &mSampler));
}

Sampler::~Sampler() {
  vkDestroySampler(mCtx.device(), mSampler, nullptr);
}

}  // namespace sky
