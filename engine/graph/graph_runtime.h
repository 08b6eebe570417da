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

// What a graph is for, which decides where its transient memory and read-back buffers live.
// A frame's stay allocated for the next frame of the same shape. A bake (noise, textures,
// LUTs) runs once, often in the middle of building a frame, in its own memory, freed when it
// is done: it never evicts the frames', so a frame never rebuilds what the last one had.
enum class GraphUse : uint8_t { Frame, Bake };

class GraphRuntime {
public:
  explicit GraphRuntime(const Context& ctx);
  ~GraphRuntime();
  GraphRuntime(const GraphRuntime&) = delete;
  GraphRuntime& operator=(const GraphRuntime&) = delete;

  const Context& gpu() const { return mCtx; }
  // Bytes of device memory held for the frames' transient resources (reports and tests).
  uint64_t transientBytes() const;
  // Times the frames' transient memory was (re)allocated: once while the graph keeps its shape.
  uint64_t transientAllocations() const { return mTransientAllocations; }

private:
  friend class FrameGraph;
  friend class PassContext;

  // Frame start: the previous frame has completed, so arenas can be reused.
  VkCommandBuffer beginFrame();
  // The same for a frame recorded into a host's command buffer (FrameGraph::record): the
  // arenas reset, and the staging of the frame the host last ran freed.
  void beginHostFrame();
  // A recorded frame's upload staging, kept until the next frame: the host runs it later.
  std::vector<std::unique_ptr<Buffer>> mHostStaging;
  void submitAndWait();
  UniformRange uploadUniform(const void* data, VkDeviceSize size);

  struct Transients {
    std::string key;  // shapes + memory plan; equal key -> reuse everything
    std::vector<VkDeviceMemory> memory;
    std::vector<Image> images;    // by resource index (empty for non-transient)
    std::vector<Buffer> buffers;  // by resource index
    uint64_t bytes = 0;
  };
  void releaseTransients(GraphUse use);
  Transients& transients(GraphUse use) { return mTransients[static_cast<int>(use)]; }
  std::vector<Buffer>& readback(GraphUse use) { return mReadback[static_cast<int>(use)]; }

  const Context& mCtx;
  VkCommandPool mPool = VK_NULL_HANDLE;
  VkCommandBuffer mCmd = VK_NULL_HANDLE;
  VkFence mFence = VK_NULL_HANDLE;
  DescriptorArena mDescriptors;
  std::vector<Buffer> mUniformChunks;
  size_t mUniformChunk = 0;
  VkDeviceSize mUniformOffset = 0;
  Transients mTransients[2];        // by GraphUse
  std::vector<Buffer> mReadback[2];  // by GraphUse
  uint64_t mTransientAllocations = 0;
};

}  // namespace sky
