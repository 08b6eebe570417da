#pragma once
// Turns a failed Vulkan call into a one-line sky::Error naming the call and the result.
#include <vulkan/vulkan.h>

#include "engine/core/error.h"

namespace sky {

const char* vkResultName(VkResult result);

#define SKY_VK(call)                                                                    \
  do {                                                                                  \
    VkResult skyVkResult_ = (call);                                                     \
    if (skyVkResult_ != VK_SUCCESS)                                                     \
      ::sky::internalError(std::string(#call).substr(0, std::string(#call).find('(')) + \
                           " failed: " + ::sky::vkResultName(skyVkResult_));            \
  } while (0)

}  // namespace sky
