#include "engine/gpu/texel_convert.h"

#include <cmath>
#include <cstring>
#include <string>

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

std::vector<uint8_t> floatsToTexels(VkFormat format, std::span<const float> pixels) {
  std::vector<uint8_t> out;
  switch (format) {
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      out.resize(pixels.size() * 4);
      std::memcpy(out.data(), pixels.data(), out.size());
      break;
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      out.resize(pixels.size() * 2);
      for (size_t i = 0; i < pixels.size(); ++i) {
        const uint16_t h = glm::packHalf1x16(pixels[i]);
        std::memcpy(out.data() + i * 2, &h, 2);
      }
      break;
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8G8B8A8_UNORM:
      out.resize(pixels.size());
      for (size_t i = 0; i < pixels.size(); ++i) {
        const float v = std::isnan(pixels[i]) ? 0.0f : std::fmin(std::fmax(pixels[i], 0.0f), 1.0f);
        out[i] = static_cast<uint8_t>(std::lround(v * 255.0f));
      }
      break;
    default:
      internalError(std::string("upload of format ") + formatName(format) + " is not supported");
  }
  return out;
}

}  // namespace sky
