#pragma once
// The frame graph as plain data: what the builder records and what every compile stage
// reads. CPU-only tests construct these directly.
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/gpu/buffer.h"
#include "engine/gpu/image.h"
#include "engine/graph/access.h"

namespace sky {

enum class ResourceKind : uint8_t { Image, Buffer };

// Where an imported (persistent) resource stands when the frame starts: its layout and the
// last write that later accesses must wait for. Carried from frame to frame by the graph.
struct ResourceState {
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkPipelineStageFlags2 writeStage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 writeAccess = VK_ACCESS_2_NONE;
  bool operator==(const ResourceState&) const = default;
};

struct ResourceNode {
  std::string name;
  ResourceKind kind = ResourceKind::Image;
  bool imported = false;
  ImageDesc image;        // kind == Image; usage is derived from the accesses for transient images
  BufferDesc buffer;      // kind == Buffer
  ResourceState initial;  // imported only
  uint32_t versions = 1;  // how many versions exist (1 + number of writes)
};

// One declared use. For a write, `version` is the version the pass overwrites and the pass
// produces version + 1.
struct ResourceAccess {
  uint32_t resource = 0;
  uint32_t version = 0;
  Access access = Access::SampledCompute;
};

struct PassNode {
  std::string name;
  std::vector<ResourceAccess> accesses;
  bool sideEffect = false;  // kept even if nothing reads its results (readback, persistent bakes)
};

struct GraphDesc {
  std::vector<ResourceNode> resources;
  std::vector<PassNode> passes;
};

}  // namespace sky
