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

}  // namespace sky::detail
