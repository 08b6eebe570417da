#pragma once
// What frame graphs keep between frames: the command buffer and fence, descriptor and
// uniform arenas, transient memory (reused while the graph's shape stays the same) and
// readback buffers. One per Context; frames execute one at a time.
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/gpu/buffer.h"
#include "engine/gpu/descriptor_arena.h"
#include "engine/gpu/image.h"

namespace sky {

class Context;

struct UniformRange {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  VkDeviceSize size = 0;
};

class GraphRuntime {
public:
  explicit GraphRuntime(const Context& ctx);
  ~GraphRuntime();
  GraphRuntime(const GraphRuntime&) = delete;
  GraphRuntime& operator=(const GraphRuntime&) = delete;

  const Context& gpu() const { return mCtx; }
  // Bytes of device memory held for transient resources (for reports and tests).
  uint64_t transientBytes() const;

private:
  friend class FrameGraph;
  friend class PassContext;

  // Frame start: the previous frame has completed, so arenas can be reused.
  VkCommandBuffer beginFrame();
  void submitAndWait();
  UniformRange uploadUniform(const void* data, VkDeviceSize size);

  struct Transients {
    std::string key;  // shapes + memory plan; equal key -> reuse everything
    std::vector<VkDeviceMemory> memory;
    std::vector<Image> images;    // by resource index (empty for non-transient)
    std::vector<Buffer> buffers;  // by resource index
    uint64_t bytes = 0;
  };
  void releaseTransients();

  const Context& mCtx;
  VkCommandPool mPool = VK_NULL_HANDLE;
  VkCommandBuffer mCmd = VK_NULL_HANDLE;
  VkFence mFence = VK_NULL_HANDLE;
  DescriptorArena mDescriptors;
  std::vector<Buffer> mUniformChunks;
  size_t mUniformChunk = 0;
  VkDeviceSize mUniformOffset = 0;
  Transients mTransients;
  std::vector<Buffer> mReadback;
};

}  // namespace sky
