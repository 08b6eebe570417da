#pragma once
// On-disk SPIR-V cache: one file per key, cacheDir()/spirv/<hex key>.spv.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <vector>

namespace sky::detail {

std::filesystem::path spirvCachePath(const std::filesystem::path& dir, uint64_t key);

// Any thread, any time. A missing, short, corrupt or foreign file is a miss, never an error.
std::optional<std::vector<uint32_t>> loadCachedSpirv(const std::filesystem::path& dir,
                                                     uint64_t key);

// Any thread, any time; writes atomically. Failures (read-only disk, full disk) are ignored:
// the cache only saves time, and the next compile simply misses again.
void storeCachedSpirv(const std::filesystem::path& dir, uint64_t key,
                      std::span<const uint32_t> spirv);

// The index from a shader's raw text (its files as they are on disk, before glslang
// preprocesses them) to the key of its SPIR-V: a process that finds its shaders unchanged
// loads them without starting glslang, whose first preprocess costs ~180 ms (the built-in
// symbol tables). cacheDir()/spirv/<hex raw key>.idx. Same rules as above: a missing or
// foreign file is a miss, a failed store is only slower.
std::optional<uint64_t> loadSourceIndex(const std::filesystem::path& dir, uint64_t rawKey);
void storeSourceIndex(const std::filesystem::path& dir, uint64_t rawKey, uint64_t sourceHash);

}  // namespace sky::detail
