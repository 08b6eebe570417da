#pragma once
// Global memory barriers recorded by hand, where no frame graph derives them: uploads and
// read-backs outside a graph, and a window's own clears and blits.
#include <vulkan/vulkan.h>

namespace sky {

// Makes `srcAccess` at `srcStage` before it available and visible to `dstAccess` at
// `dstStage` after it.
inline void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage,
                          VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                          VkAccessFlags2 dstAccess) {
  VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

// Copies recorded before it into host-visible buffers (read-backs) are visible to the host
// once the submit's fence has signalled.
inline void copiesVisibleToHost(VkCommandBuffer cmd) {
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

}  // namespace sky
