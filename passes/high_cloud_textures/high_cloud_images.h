#pragma once
// Files behind HighCloudTextures: the scene's coefficient, normal and cover-map images and
// the procedural bake's disk cache entries. Formats and decoding are in docs/high-clouds.md.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sky::high_clouds {

// Square textures the GPU takes: a power of two within these bounds.
constexpr uint32_t kMinSize = 16;
constexpr uint32_t kMaxSize = 8192;

// Interleaved floats, row 0 = top (north).
struct Texture {
  uint32_t width = 0, height = 0, channels = 0;
  std::vector<float> pixels;
};

// The coefficient image at `path` (`key`, e.g. "high_clouds.coefficients", and `written`, the
// path as the scene wrote it, name it in errors): a PNG (8-bit codes / 255) or EXR (as is)
// with 4 channels, square, a power of two in [kMinSize, kMaxSize]. BadInput otherwise.
Texture readCoefficients(const std::filesystem::path& path, const std::string& key,
                         const std::string& written);

// The normal map at `path`, `size` x `size`: PNG RGB/RGBA decoded as n = 2c - 1 (c = code /
// 255), EXR RGB/RGBA taken as is; normalised (a zero vector becomes (0, 0, 1)). Returns RGBA
// with w = 0.
Texture readNormals(const std::filesystem::path& path, const std::string& key,
                    const std::string& written, uint32_t size);

// A greyscale cover map, any size: grey (+alpha) as is, RGB(A) through Rec. 709 luminance;
// PNG codes / 255, EXR as is; clamped to [0, 1]. One channel.
Texture readCoverMap(const std::filesystem::path& path, const std::string& key,
                     const std::string& written);

// Size and modification time of a file, or "missing": what tells addTo that an input changed
// without reading it.
std::string fileStamp(const std::filesystem::path& path);

// A bake's cache entry, N x N, RGBA each: coefficients, normals (xyz; w = 0 on reading) and
// rank/shape (rank, shape; b = a = 0 on reading).
struct CacheEntry {
  uint32_t size = 0;
  std::vector<float> coefficients;
  std::vector<float> normals;
  std::vector<float> rankShape;
};
// nullopt when the file is missing, unreadable, of another key or size, or holds non-finite
// values: the caller bakes again and overwrites it.
std::optional<CacheEntry> readCacheEntry(const std::filesystem::path& path, const std::string& key,
                                         uint32_t size);
// Writes atomically (HALF EXR, the precision of the textures); BadInput if it cannot.
void writeCacheEntry(const std::filesystem::path& path, const std::string& key,
                     const CacheEntry& entry);

}  // namespace sky::high_clouds
