#pragma once
// The frame-graph compiler, one small stage per function; each returns plain data so a
// CPU-only test can check it. FrameGraph::compile() runs them in this order.
#include <cstdint>
#include <vector>

#include "engine/graph/graph_desc.h"

namespace sky {

// Keeps only passes that a side-effect pass (readback of a requested output, a persistent
// bake) needs, so debug outputs and unused layers cost nothing unless asked for.
std::vector<bool> cull(const GraphDesc& graph);

// Topological order of the live passes from their data dependencies (read-after-write,
// write-after-read, write-after-write). Ties keep declaration order, so recording is
// predictable. A cycle is an error naming the passes on it.
std::vector<uint32_t> order(const GraphDesc& graph, const std::vector<bool>& alive);

// First and last position (index into the order) at which each resource is used; unused
// resources have first = -1. Transient memory can be shared outside these intervals.
struct Lifetime {
  int first = -1;
  int last = -1;
  bool used() const { return first >= 0; }
  bool operator==(const Lifetime&) const = default;
};
std::vector<Lifetime> computeLifetimes(const GraphDesc& graph, const std::vector<uint32_t>& order);

// Memory for transient resources: resources whose lifetimes do not overlap share a slot.
// Images share only with images, buffers with buffers, and only where memory types agree.
struct MemoryRequirement {
  uint64_t size = 0;
  uint64_t alignment = 1;
  uint32_t typeBits = ~0u;
};
struct MemorySlot {
  ResourceKind kind = ResourceKind::Image;
  uint64_t size = 0;
  uint64_t alignment = 1;
  uint32_t typeBits = ~0u;
  std::vector<uint32_t> residents;  // resource indices in order of first use
};
struct MemoryPlan {
  std::vector<int> slotOf;  // per resource: slot index, -1 for imported or unused
  std::vector<MemorySlot> slots;
  uint64_t totalBytes() const;
};
// `requirements` is indexed by resource (entries of imported/unused resources are ignored).
MemoryPlan assignMemory(const GraphDesc& graph, const std::vector<Lifetime>& lifetimes,
                        const std::vector<MemoryRequirement>& requirements);

// Every barrier and layout transition, derived from the declared accesses only.
struct Barrier {
  uint32_t resource = 0;
  VkPipelineStageFlags2 srcStage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 srcAccess = VK_ACCESS_2_NONE;
  VkPipelineStageFlags2 dstStage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 dstAccess = VK_ACCESS_2_NONE;
  VkImageLayout oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // both UNDEFINED for buffers
  VkImageLayout newLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  bool operator==(const Barrier&) const = default;
};
struct BarrierPlan {
  std::vector<std::vector<Barrier>> before;  // per position in the order
  std::vector<ResourceState> finalState;     // per resource, after the last pass
};
BarrierPlan buildBarriers(const GraphDesc& graph, const std::vector<uint32_t>& order,
                          const MemoryPlan& memory);

}  // namespace sky
