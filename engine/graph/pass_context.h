#pragma once
// What a pass's execute() gets: the command buffer, the resources it declared, uniform
// uploads and one call that binds a pipeline's descriptors and dispatches. Passes record
// commands only; a resource that setup() did not declare is an error here.
#include <cstdint>
#include <initializer_list>
#include <span>

#include <vulkan/vulkan.h>

#include "engine/graph/graph_runtime.h"
#include "engine/graph/handle.h"

namespace sky {

class ComputePipeline;
class Context;
class FrameGraph;
class Sampler;

// One descriptor for PassContext::dispatch. The descriptor type comes from the shader's
// reflection; the image layout from the access the pass declared.
struct Binding {
  enum class Kind : uint8_t { Image, Buffer, Uniform };
  uint32_t binding = 0;
  Kind kind = Kind::Image;
  ImageId image;
  BufferId buffer;
  UniformRange uniform;
  const Sampler* sampler = nullptr;

  static Binding of(uint32_t b, ImageId h, const Sampler* s = nullptr) {
    return {.binding = b, .kind = Kind::Image, .image = h, .sampler = s};
  }
  static Binding of(uint32_t b, BufferId h) {
    return {.binding = b, .kind = Kind::Buffer, .buffer = h};
  }
  static Binding of(uint32_t b, UniformRange u) {
    return {.binding = b, .kind = Kind::Uniform, .uniform = u};
  }
};

class PassContext {
public:
  VkCommandBuffer cmd() const { return mCmd; }
  const Context& gpu() const;
  const Image& image(ImageId handle) const;
  const Buffer& buffer(BufferId handle) const;
  // Copies `data` into this frame's uniform arena; the range binds to a uniform block (the
  // passes' parameter blocks, shaders/common/params_block.glsl) or a read-only storage block.
  UniformRange uniform(const void* data, VkDeviceSize size) const;
  template <class T>
  UniformRange uniform(const T& value) const {
    return uniform(&value, sizeof(T));
  }
  // Binds `pipeline`, writes every binding its shader declares (all must be given, types
  // must match the reflection), pushes constants and dispatches `groups`.
  void dispatch(const ComputePipeline& pipeline, std::span<const Binding> bindings,
                uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ = 1,
                const void* pushConstants = nullptr, uint32_t pushSize = 0) const;
  void dispatch(const ComputePipeline& pipeline, std::initializer_list<Binding> bindings,
                uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ = 1,
                const void* pushConstants = nullptr, uint32_t pushSize = 0) const {
    dispatch(pipeline, std::span<const Binding>(bindings.begin(), bindings.size()), groupsX,
             groupsY, groupsZ, pushConstants, pushSize);
  }

private:
  friend class FrameGraph;
  PassContext(FrameGraph& graph, uint32_t pass, VkCommandBuffer cmd)
      : mGraph(graph), mPass(pass), mCmd(cmd) {}
  const struct ResourceAccess* declared(uint32_t resource) const;

  FrameGraph& mGraph;
  uint32_t mPass;
  VkCommandBuffer mCmd;
};

}  // namespace sky
