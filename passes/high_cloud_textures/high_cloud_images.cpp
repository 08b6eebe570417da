#include "passes/high_cloud_textures/high_cloud_images.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>

#include "engine/core/error.h"
#include "engine/io/exr.h"
#include "engine/io/png.h"

namespace sky::high_clouds {
namespace {
namespace fs = std::filesystem;

const char* kKeyAttribute = "skylayers:high_clouds_key";

// Names the setting and the file as the scene wrote it; the reader's message already starts
// with the resolved path, which is dropped to keep one short line.
[[noreturn]] void fail(const std::string& key, const std::string& written,
                       const std::string& what) {
  inputError(key + ": " + written + ": " + what);
}

std::string extensionOf(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Any image as floats with its own channel count: PNG codes / 255, EXR's main (or first) layer.
Texture readAny(const fs::path& path, const std::string& key, const std::string& written) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(key, written, "file not found (" + path.string() + ")");
  const std::string ext = extensionOf(path);
  if (ext != ".png" && ext != ".exr") fail(key, written, "must be a PNG or EXR file");
  Texture t;
  try {
    if (ext == ".png") {
      Image8 png = readPng(path);
      t.width = static_cast<uint32_t>(png.width);
      t.height = static_cast<uint32_t>(png.height);
      t.channels = static_cast<uint32_t>(png.channels);
      t.pixels.resize(png.pixels.size());
      for (size_t i = 0; i < png.pixels.size(); ++i) t.pixels[i] = png.pixels[i] / 255.0f;
    } else {
      LayeredImage exr = readExr(path);
      const ImageLayer* layer = exr.find("");
      if (!layer) layer = &exr.layers.front();
      t.width = static_cast<uint32_t>(exr.width);
      t.height = static_cast<uint32_t>(exr.height);
      t.channels = static_cast<uint32_t>(layer->channels.size());
      t.pixels = layer->pixels;
    }
  } catch (const Error& e) {
    std::string what = e.what();
    const std::string prefix = path.string() + ": ";
    if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
    fail(key, written, what);
  }
  for (float v : t.pixels)
    if (!std::isfinite(v)) fail(key, written, "holds a NaN or infinite value");
  return t;
}

bool powerOfTwo(uint32_t v) {
  return v != 0 && (v & (v - 1)) == 0;
}

std::string sizeText(const Texture& t) {
  return std::to_string(t.width) + "x" + std::to_string(t.height);
}

}  // namespace

Texture readCoefficients(const fs::path& path, const std::string& key, const std::string& written) {
  Texture t = readAny(path, key, written);
  if (t.channels != 4)
    fail(key, written, "must be RGBA (4 channels), has " + std::to_string(t.channels));
  if (t.width != t.height) fail(key, written, "must be square, is " + sizeText(t));
  if (!powerOfTwo(t.width) || t.width < kMinSize || t.width > kMaxSize)
    fail(key, written,
         "size " + sizeText(t) + " must be a power of two from " + std::to_string(kMinSize) +
             " to " + std::to_string(kMaxSize));
  return t;
}

Texture readNormals(const fs::path& path, const std::string& key, const std::string& written,
                    uint32_t size) {
  Texture t = readAny(path, key, written);
  if (t.channels != 3 && t.channels != 4)
    fail(key, written, "must be RGB or RGBA (3 or 4 channels), has " + std::to_string(t.channels));
  if (t.width != size || t.height != size)
    fail(key, written,
         "size " + sizeText(t) + " differs from the coefficients' " + std::to_string(size) + "x" +
             std::to_string(size));
  const bool encoded = extensionOf(path) == ".png";
  Texture out{size, size, 4, std::vector<float>(size_t(size) * size * 4)};
  for (size_t i = 0; i < size_t(size) * size; ++i) {
    float n[3];
    for (int c = 0; c < 3; ++c) {
      const float v = t.pixels[i * t.channels + c];
      n[c] = encoded ? 2.0f * v - 1.0f : v;  // 8-bit codes store [-1, 1] as [0, 1]
    }
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int c = 0; c < 3; ++c) out.pixels[i * 4 + c] = len > 0 ? n[c] / len : (c == 2 ? 1.f : 0.f);
    out.pixels[i * 4 + 3] = 0.0f;
  }
  return out;
}

Texture readCoverMap(const fs::path& path, const std::string& key, const std::string& written) {
  Texture t = readAny(path, key, written);
  Texture out{t.width, t.height, 1, std::vector<float>(size_t(t.width) * t.height)};
  for (size_t i = 0; i < out.pixels.size(); ++i) {
    const float* p = &t.pixels[i * t.channels];
    // Rec. 709 luminance weights for colour images; grey (and grey + alpha) as it is.
    const float v = t.channels >= 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
    out.pixels[i] = std::clamp(v, 0.0f, 1.0f);
  }
  return out;
}

std::string fileStamp(const fs::path& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) return "missing";
  const auto time = fs::last_write_time(path, ec);
  if (ec) return "missing";
  return std::to_string(size) + "@" + std::to_string(time.time_since_epoch().count());
}

std::optional<CacheEntry> readCacheEntry(const fs::path& path, const std::string& key,
                                         uint32_t size) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  LayeredImage exr;
  try {
    exr = readExr(path);
  } catch (const Error&) {
    return std::nullopt;  // corrupt or truncated: bake again
  }
  const auto stored = exr.attributes.find(kKeyAttribute);
  if (stored == exr.attributes.end() || stored->second != key) return std::nullopt;
  if (exr.width != int(size) || exr.height != int(size)) return std::nullopt;
  const ImageLayer* coefficients = exr.find("");
  const ImageLayer* normals = exr.find("normals");
  const ImageLayer* rankShape = exr.find("rank_shape");
  if (!coefficients || !normals || !rankShape ||
      coefficients->channels != std::vector<std::string>{"R", "G", "B", "A"} ||
      normals->channels != std::vector<std::string>{"X", "Y", "Z"} ||
      rankShape->channels != std::vector<std::string>{"rank", "shape"})
    return std::nullopt;
  const size_t texels = size_t(size) * size;
  CacheEntry entry{size, coefficients->pixels, std::vector<float>(texels * 4),
                   std::vector<float>(texels * 4)};
  for (size_t i = 0; i < texels; ++i) {
    for (int c = 0; c < 3; ++c) entry.normals[i * 4 + c] = normals->pixels[i * 3 + c];
    entry.normals[i * 4 + 3] = 0.0f;
    for (int c = 0; c < 2; ++c) entry.rankShape[i * 4 + c] = rankShape->pixels[i * 2 + c];
    entry.rankShape[i * 4 + 2] = entry.rankShape[i * 4 + 3] = 0.0f;
  }
  for (const std::vector<float>* image : {&entry.coefficients, &entry.normals, &entry.rankShape})
    for (float v : *image)
      if (!std::isfinite(v)) return std::nullopt;
  return entry;
}

void writeCacheEntry(const fs::path& path, const std::string& key, const CacheEntry& entry) {
  const size_t texels = size_t(entry.size) * entry.size;
  if (entry.coefficients.size() != texels * 4 || entry.normals.size() != texels * 4 ||
      entry.rankShape.size() != texels * 4)
    internalError("high-cloud cache entry of the wrong size");
  LayeredImage exr;
  exr.width = exr.height = int(entry.size);
  exr.attributes[kKeyAttribute] = key;
  exr.layers.push_back({"", {"R", "G", "B", "A"}, entry.coefficients});
  ImageLayer normals{"normals", {"X", "Y", "Z"}, std::vector<float>(texels * 3)};
  for (size_t i = 0; i < texels; ++i)
    for (int c = 0; c < 3; ++c) normals.pixels[i * 3 + c] = entry.normals[i * 4 + c];
  exr.layers.push_back(std::move(normals));
  ImageLayer rankShape{"rank_shape", {"rank", "shape"}, std::vector<float>(texels * 2)};
  for (size_t i = 0; i < texels; ++i)
    for (int c = 0; c < 2; ++c) rankShape.pixels[i * 2 + c] = entry.rankShape[i * 4 + c];
  exr.layers.push_back(std::move(rankShape));
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);  // a failure shows up as writeExr's error
  writeExr(path, exr);
}

}  // namespace sky::high_clouds
