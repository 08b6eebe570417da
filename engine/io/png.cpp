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

uint8_t toByte(float v) {
  if (!(v > 0.0f)) return 0;  // also catches NaN
  if (v >= 1.0f) return 255;
  return static_cast<uint8_t>(std::lround(v * 255.0f));
}

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

}  // namespace

void writePng8(const fs::path& path, int width, int height, std::span<const float> displayRgba) {
  if (width <= 0 || height <= 0)
    internalError("writePng8: " + path.string() + ": image size " + std::to_string(width) + "x" +
                  std::to_string(height) + " is empty");
  const size_t values = size_t(width) * size_t(height) * 4;
  if (displayRgba.size() != values)
    internalError("writePng8: " + path.string() + ": " + std::to_string(displayRgba.size()) +
                  " values for a " + std::to_string(width) + "x" + std::to_string(height) +
                  " RGBA image (expected " + std::to_string(values) + ")");

  std::vector<uint8_t> bytes(values);
  std::transform(displayRgba.begin(), displayRgba.end(), bytes.begin(), toByte);

  // Encoded in memory so the file itself goes through writeFileAtomic like every output.
  std::string encoded;
  if (!stbi_write_png_to_func(appendBytes, &encoded, width, height, 4, bytes.data(), width * 4))
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
