#pragma once
// A buffer with its own memory: device-local, or host-visible and persistently mapped
// (uniform uploads, readback). Move-only.
#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

#include "engine/gpu/image.h"

namespace sky {

class Context;

enum class BufferMemory : uint8_t { Device, HostVisible };

// For debug output only: a buffer that holds an image (one 32-bit unsigned value per texel,
// row 0 the top, from `offset` bytes on) can be asked for by name like an image and is shown
// as one (`view`), each value times `scale`. Width 0: the buffer holds no image and is not
// viewable (a star catalogue, a list).
struct BufferImage {
  uint32_t width = 0, height = 0;
  VkDeviceSize offset = 0;
  float scale = 1.0f;
  DebugView view = DebugView::Scalar;
  std::string about;
};

struct BufferDesc {
  std::string name;
  VkDeviceSize size = 0;
  VkBufferUsageFlags usage = 0;
  BufferMemory memory = BufferMemory::Device;
  BufferImage image;
};

class Buffer {
public:
  Buffer() = default;
  // With `allocate` false the buffer gets memory later through bindMemory (frame-graph
  // aliasing of transient buffers); only Device buffers can be unallocated.
  Buffer(const Context& ctx, const BufferDesc& desc, bool allocate = true);
  ~Buffer();
  Buffer(Buffer&& o) noexcept { *this = std::move(o); }
  Buffer& operator=(Buffer&& o) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  void bindMemory(VkDeviceMemory memory, VkDeviceSize offset);

  const BufferDesc& desc() const { return mDesc; }
  VkBuffer buffer() const { return mBuffer; }
  VkDeviceSize size() const { return mDesc.size; }
  // Host pointer for HostVisible buffers (coherent, mapped for the buffer's lifetime).
  void* mapped() const { return mMapped; }
  // Makes device writes visible to the host for non-coherent memory; a no-op when coherent.
  void invalidate() const;
  explicit operator bool() const { return mBuffer != VK_NULL_HANDLE; }

private:
  void reset();

  const Context* mCtx = nullptr;
  BufferDesc mDesc;
  VkBuffer mBuffer = VK_NULL_HANDLE;
  VkDeviceMemory mMemory = VK_NULL_HANDLE;
  void* mMapped = nullptr;
  bool mCoherent = true;
};

}  // namespace sky
