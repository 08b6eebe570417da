#include "engine/io/png.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace sky {
namespace fs = std::filesystem;

namespace {

// An 8-bit code for v in [0, 1] plus `offset` codes before rounding (NaN -> 0).
uint8_t toByte(float v, float offset) {
  if (!(v == v)) return 0;
  const float code = std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f + offset);
  return static_cast<uint8_t>(std::clamp(code, 0.0f, 255.0f));
}

// Uniform in [0, 1) from a hash of (x, y, channel) (PCG3D, Jarzynski & Olano 2020).
float hashUniform(uint32_t x, uint32_t y, uint32_t z) {
  uint32_t a = x * 1664525u + 1013904223u, b = y * 1664525u + 1013904223u,
           c = z * 1664525u + 1013904223u;
  a += b * c;
  b += c * a;
  c += a * b;
  a ^= a >> 16u;
  b ^= b >> 16u;
  c ^= c >> 16u;
  a += b * c;
  b += c * a;
  c += a * b;
  return static_cast<float>(a >> 8u) * (1.0f / 16777216.0f);
}

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

}  // namespace

std::vector<uint8_t> quantize8(int width, int height, std::span<const float> displayRgba,
                               PngQuantize quantize) {
  const size_t values = size_t(std::max(width, 0)) * size_t(std::max(height, 0)) * 4;
  if (width <= 0 || height <= 0 || displayRgba.size() != values)
    internalError("quantize8: " + std::to_string(displayRgba.size()) + " values for a " +
                  std::to_string(width) + "x" + std::to_string(height) + " RGBA image");
  std::vector<uint8_t> bytes(values);
  for (size_t i = 0; i < values; ++i) {
    float offset = 0.0f;
    const uint32_t channel = static_cast<uint32_t>(i % 4);
    if (quantize == PngQuantize::Dither && channel < 3) {
      // Triangular in (-1, 1) codes: the sum of two uniforms.
      const uint32_t pixel = static_cast<uint32_t>(i / 4);
      const uint32_t x = pixel % static_cast<uint32_t>(width);
      const uint32_t y = pixel / static_cast<uint32_t>(width);
      offset = hashUniform(x, y, 2u * channel) + hashUniform(x, y, 2u * channel + 1u) - 1.0f;
    }
    bytes[i] = toByte(displayRgba[i], offset);
  }
  return bytes;
}

void writePng8(const fs::path& path, int width, int height, std::span<const float> displayRgba,
               PngQuantize quantize) {
  if (width <= 0 || height <= 0)
    internalError("writePng8: " + path.string() + ": image size " + std::to_string(width) + "x" +
                  std::to_string(height) + " is empty");
  const size_t values = size_t(width) * size_t(height) * 4;
  if (displayRgba.size() != values)
    internalError("writePng8: " + path.string() + ": " + std::to_string(displayRgba.size()) +
                  " values for a " + std::to_string(width) + "x" + std::to_string(height) +
                  " RGBA image (expected " + std::to_string(values) + ")");
  writePngCodes(path, width, height, quantize8(width, height, displayRgba, quantize));
}

void writePngCodes(const fs::path& path, int width, int height, std::span<const uint8_t> rgba) {
  if (width <= 0 || height <= 0 || rgba.size() != size_t(width) * size_t(height) * 4)
    internalError("writePngCodes: " + path.string() + ": " + std::to_string(rgba.size()) +
                  " codes for a " + std::to_string(width) + "x" + std::to_string(height) +
                  " RGBA image");
  // Encoded in memory so the file itself goes through writeFileAtomic like every output.
  std::string encoded;
  if (!stbi_write_png_to_func(appendBytes, &encoded, width, height, 4, rgba.data(), width * 4))
    internalError("writePng8: " + path.string() + ": PNG encoding failed");
  writeFileAtomic(path, encoded);
}

Image8 readPng(const fs::path& path) {
  const std::vector<uint8_t> file = readBinaryFile(path);
  if (file.size() > size_t(INT32_MAX)) inputError(path.string() + ": PNG file is too large");
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> data(
      stbi_load_from_memory(file.data(), int(file.size()), &w, &h, &channels, 0), stbi_image_free);
  if (!data) {
    const char* reason = stbi_failure_reason();
    inputError(path.string() + ": cannot read PNG: " + (reason ? reason : "unknown error"));
  }
  Image8 image{w, h, channels, {}};
  image.pixels.assign(data.get(), data.get() + size_t(w) * size_t(h) * size_t(channels));
  return image;
}

}  // namespace sky
