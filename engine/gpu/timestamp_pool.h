#pragma once
// GPU timestamps: pairs of queries around each recorded span; read back after the fence.
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace sky {

class Context;

class TimestampPool {
public:
  TimestampPool(const Context& ctx, uint32_t spans);
  ~TimestampPool();
  TimestampPool(const TimestampPool&) = delete;
  TimestampPool& operator=(const TimestampPool&) = delete;

  uint32_t spans() const { return mSpans; }
  // Recorded at the start of the command buffer, before any begin()/end().
  void reset(VkCommandBuffer cmd);
  void begin(VkCommandBuffer cmd, uint32_t span);
  void end(VkCommandBuffer cmd, uint32_t span);
  // Milliseconds per span, after the submission has completed. Empty without timestamps.
  std::vector<double> resultsMs() const;

private:
  const Context& mCtx;
  uint32_t mSpans;
  VkQueryPool mPool = VK_NULL_HANDLE;
};

}  // namespace sky
