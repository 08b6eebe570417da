#include "engine/shader/detail/spirv_cache.h"

#include <cstring>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

#include "engine/core/files.h"
#include "engine/core/paths.h"

namespace sky::detail {
namespace fs = std::filesystem;

namespace {
// File layout: a 32-byte header {magic, key, checksum of the payload, word count} then the
// SPIR-V words. The checksum catches torn or bit-rotted files that still have the right
// size; the key catches a file copied under the wrong name.
constexpr uint64_t kMagic = 0x31305650534b5953ull;  // "SKYSPV01" little-endian
constexpr size_t kHeaderWords64 = 4;
constexpr size_t kHeaderBytes = kHeaderWords64 * sizeof(uint64_t);
constexpr uint32_t kSpirvMagic = 0x07230203u;

uint64_t checksum(std::span<const uint32_t> words) {
  return hash64(std::string_view(reinterpret_cast<const char*>(words.data()), words.size_bytes()));
}
}  // namespace

fs::path spirvCachePath(const fs::path& dir, uint64_t key) {
  return dir / (hex64(key) + ".spv");
}

std::optional<std::vector<uint32_t>> loadCachedSpirv(const fs::path& dir, uint64_t key) {
  std::ifstream in(spirvCachePath(dir, key), std::ios::binary);
  if (!in) return std::nullopt;
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad() || bytes.size() < kHeaderBytes + 5 * sizeof(uint32_t)) return std::nullopt;

  uint64_t header[kHeaderWords64];
  std::memcpy(header, bytes.data(), kHeaderBytes);
  if (header[0] != kMagic || header[1] != key) return std::nullopt;
  size_t payload = bytes.size() - kHeaderBytes;
  if (payload % sizeof(uint32_t) != 0 || header[3] != payload / sizeof(uint32_t))
    return std::nullopt;

  std::vector<uint32_t> words(payload / sizeof(uint32_t));
  std::memcpy(words.data(), bytes.data() + kHeaderBytes, payload);
  if (words[0] != kSpirvMagic || checksum(words) != header[2]) return std::nullopt;
  return words;
}

void storeCachedSpirv(const fs::path& dir, uint64_t key, std::span<const uint32_t> spirv) {
  uint64_t header[kHeaderWords64] = {kMagic, key, checksum(spirv), spirv.size()};
  std::string bytes(reinterpret_cast<const char*>(header), kHeaderBytes);
  bytes.append(reinterpret_cast<const char*>(spirv.data()), spirv.size_bytes());
  try {
    std::error_code ec;
    fs::create_directories(dir, ec);
    writeFileAtomic(spirvCachePath(dir, key), bytes);
  } catch (const std::exception& e) {
    // Not an error, see the header: a cache that cannot be written is only slower. The
    // render's report and warning say so (cacheStatus).
    noteCacheWriteFailed(e.what());
  }
}

namespace {
constexpr uint64_t kIndexMagic = 0x31304352534b5953ull;  // "SKYSRC01" little-endian
}

std::optional<uint64_t> loadSourceIndex(const fs::path& dir, uint64_t rawKey) {
  std::ifstream in(dir / (hex64(rawKey) + ".idx"), std::ios::binary);
  if (!in) return std::nullopt;
  uint64_t words[4] = {};
  in.read(reinterpret_cast<char*>(words), sizeof words);
  if (in.gcount() != sizeof words || in.peek() != std::char_traits<char>::eof())
    return std::nullopt;
  // {magic, raw key, SPIR-V key, a check of the two}: a torn or copied file is a miss.
  if (words[0] != kIndexMagic || words[1] != rawKey || words[3] != (rawKey ^ ~words[2]))
    return std::nullopt;
  return words[2];
}

void storeSourceIndex(const fs::path& dir, uint64_t rawKey, uint64_t sourceHash) {
  const uint64_t words[4] = {kIndexMagic, rawKey, sourceHash, rawKey ^ ~sourceHash};
  try {
    std::error_code ec;
    fs::create_directories(dir, ec);
    writeFileAtomic(dir / (hex64(rawKey) + ".idx"),
                    std::string(reinterpret_cast<const char*>(words), sizeof words));
  } catch (const std::exception& e) {
    noteCacheWriteFailed(e.what());
  }
}

}  // namespace sky::detail
