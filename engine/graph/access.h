#pragma once
// How a pass uses a resource. Everything else — pipeline stages, access masks, image
// layouts, usage flags and so every barrier — is derived from this one value.
#include <cstdint>

#include <vulkan/vulkan.h>

namespace sky {

enum class Access : uint8_t {
  SampledCompute,           // texture()/texelFetch through a sampler in a compute shader
  StorageReadCompute,       // imageLoad or a read-only SSBO
  StorageWriteCompute,      // imageStore or a write-only SSBO
  StorageReadWriteCompute,  // both in one pass
  UniformCompute,           // a uniform buffer (buffers only)
  TransferSrc,              // copy source (readback)
  TransferDst,              // copy destination (uploads)
};

struct AccessInfo {
  VkPipelineStageFlags2 stage;
  VkAccessFlags2 access;
  VkImageLayout layout;  // images only
  bool write;
  VkImageUsageFlags imageUsage;
  VkBufferUsageFlags bufferUsage;
  const char* name;
};

const AccessInfo& accessInfo(Access access);

}  // namespace sky
