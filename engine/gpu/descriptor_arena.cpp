#include "engine/gpu/descriptor_arena.h"

#include "engine/gpu/context.h"
#include "engine/gpu/vk_check.h"

namespace sky {

DescriptorArena::DescriptorArena(const Context& ctx) : mCtx(ctx) {}

DescriptorArena::~DescriptorArena() {
  for (VkDescriptorPool p : mPools) vkDestroyDescriptorPool(mCtx.device(), p, nullptr);
}

VkDescriptorPool DescriptorArena::newPool() {
  const VkDescriptorPoolSize sizes[] = {
      {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 128}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 128},
      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 256},  {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 256},
      {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 64},   {VK_DESCRIPTOR_TYPE_SAMPLER, 64},
  };
  VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  info.maxSets = 64;
  info.poolSizeCount = static_cast<uint32_t>(std::size(sizes));
  info.pPoolSizes = sizes;
  VkDescriptorPool pool;
  SKY_VK(vkCreateDescriptorPool(mCtx.device(), &info, nullptr, &pool));
  mPools.push_back(pool);
  return pool;
}

VkDescriptorSet DescriptorArena::allocate(VkDescriptorSetLayout layout) {
  for (;; ++mCurrent) {
    VkDescriptorPool pool = mCurrent < mPools.size() ? mPools[mCurrent] : newPool();
    VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    info.descriptorPool = pool;
    info.descriptorSetCount = 1;
    info.pSetLayouts = &layout;
    VkDescriptorSet set;
    VkResult r = vkAllocateDescriptorSets(mCtx.device(), &info, &set);
    if (r == VK_SUCCESS) return set;
    if (r != VK_ERROR_OUT_OF_POOL_MEMORY && r != VK_ERROR_FRAGMENTED_POOL) SKY_VK(r);
  }
}

void DescriptorArena::reset() {
  for (VkDescriptorPool p : mPools) SKY_VK(vkResetDescriptorPool(mCtx.device(), p, 0));
  mCurrent = 0;
}

}  // namespace sky
