#pragma once
// Descriptor sets for one frame: allocated while recording, all freed at once by reset()
// after the frame's fence. Grows by adding pools, never fails for lack of space.
#include <vector>

#include <vulkan/vulkan.h>

namespace sky {

class Context;

class DescriptorArena {
public:
  explicit DescriptorArena(const Context& ctx);
  ~DescriptorArena();
  DescriptorArena(const DescriptorArena&) = delete;
  DescriptorArena& operator=(const DescriptorArena&) = delete;

  VkDescriptorSet allocate(VkDescriptorSetLayout layout);
  // Only once the GPU has finished with every set handed out since the last reset.
  void reset();

private:
  VkDescriptorPool newPool();

  const Context& mCtx;
  std::vector<VkDescriptorPool> mPools;
  size_t mCurrent = 0;
};

}  // namespace sky
