#include "engine/gpu/timestamp_pool.h"

#include "engine/gpu/context.h"
#include "engine/gpu/vk_check.h"

namespace sky {

TimestampPool::TimestampPool(const Context& ctx, uint32_t spans) : mCtx(ctx), mSpans(spans) {
  if (!ctx.hasTimestamps() || spans == 0) return;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = spans * 2;
  SKY_VK(vkCreateQueryPool(ctx.device(), &info, nullptr, &mPool));
}

TimestampPool::~TimestampPool() {
  if (mPool) vkDestroyQueryPool(mCtx.device(), mPool, nullptr);
}

void TimestampPool::reset(VkCommandBuffer cmd) {
  if (mPool) vkCmdResetQueryPool(cmd, mPool, 0, mSpans * 2);
}

void TimestampPool::begin(VkCommandBuffer cmd, uint32_t span) {
  // Top of pipe for the start: nothing of this span has begun yet.
  if (mPool) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, mPool, span * 2);
}

void TimestampPool::end(VkCommandBuffer cmd, uint32_t span) {
  if (mPool) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, mPool, span * 2 + 1);
}

std::vector<double> TimestampPool::resultsMs() const {
  if (!mPool) return {};
  std::vector<uint64_t> ticks(mSpans * 2);
  SKY_VK(vkGetQueryPoolResults(mCtx.device(), mPool, 0, mSpans * 2, ticks.size() * sizeof(uint64_t),
                               ticks.data(), sizeof(uint64_t),
                               VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  std::vector<double> ms(mSpans);
  for (uint32_t i = 0; i < mSpans; ++i) {
    uint64_t a = ticks[i * 2], b = ticks[i * 2 + 1];
    ms[i] = b > a ? static_cast<double>(b - a) * mCtx.timestampPeriodNs() * 1e-6 : 0.0;
  }
  return ms;
}

}  // namespace sky
