#pragma once
// The disk cache of CloudNoise's textures: one file per model, raw RGBA8 bytes behind a
// header, closed by a checksum (docs/cloud-noise.md, "The cache").
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/clouds/noise_volume.h"

namespace sky::cloud_noise {

// The three textures of one model as bytes: the shape and detail volumes and the N^2 curl
// texture (RGBA8, x fastest).
struct CacheEntry {
  NoiseVolume shape;
  NoiseVolume detail;
  uint32_t curlSize = 0;
  std::vector<uint8_t> curl;
};

// The entry at `path` if it is complete and intact and holds `key` with these sizes;
// otherwise (absent, unreadable, truncated, corrupt, another key or size) nullopt, never an
// error: the caller bakes again.
std::optional<CacheEntry> readCacheEntry(const std::filesystem::path& path, const std::string& key,
                                         uint32_t shapeSize, uint32_t detailSize,
                                         uint32_t curlSize);
// Writes `entry` atomically (a temporary file renamed over `path`), creating the folder.
// Throws Error when it cannot (an unwritable cache folder).
void writeCacheEntry(const std::filesystem::path& path, const std::string& key,
                     const CacheEntry& entry);

}  // namespace sky::cloud_noise
