#include "engine/gpu/texel_convert.h"

#include <cstring>

#include <glm/gtc/packing.hpp>

#include "engine/core/error.h"
#include "engine/gpu/image.h"

namespace sky {

float halfToFloat(uint16_t h) {
  return glm::unpackHalf1x16(h);
}

std::vector<float> texelsToFloat(VkFormat format, std::span<const uint8_t> bytes) {
  std::vector<float> out;
  switch (format) {
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      out.resize(bytes.size() / 4);
      std::memcpy(out.data(), bytes.data(), out.size() * 4);
      break;
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      out.resize(bytes.size() / 2);
      for (size_t i = 0; i < out.size(); ++i) {
        uint16_t h;
        std::memcpy(&h, bytes.data() + i * 2, 2);
        out[i] = halfToFloat(h);
      }
      break;
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8G8B8A8_UNORM:
      out.resize(bytes.size());
      for (size_t i = 0; i < out.size(); ++i) out[i] = bytes[i] / 255.0f;
      break;
    default:
      internalError(std::string("read-back of format ") + formatName(format) + " is not supported");
  }
  return out;
}

}  // namespace sky
