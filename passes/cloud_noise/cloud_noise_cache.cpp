#include "passes/cloud_noise/cloud_noise_cache.h"

#include <cstring>
#include <string_view>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace sky::cloud_noise {
namespace {
namespace fs = std::filesystem;

// File layout, all integers little-endian (the byte order of every machine we build for):
//   8 bytes   magic "SKYNOISE"
//   u32       format version
//   u32       key length L, then L bytes of key
//   u32 x 3   shape, detail and curl sizes
//   bytes     shape (size^3 * 4), detail (size^3 * 4), curl (size^2 * 4)
//   u64       FNV-1a (hash64) of everything before it
// A bumped version or another key makes old entries misses, never errors.
constexpr char kMagic[8] = {'S', 'K', 'Y', 'N', 'O', 'I', 'S', 'E'};
constexpr uint32_t kVersion = 1;

size_t volumeBytes(uint32_t n) {
  return size_t(n) * n * n * 4;
}

class Reader {
public:
  explicit Reader(const std::vector<uint8_t>& bytes) : mBytes(bytes) {}
  bool read(void* out, size_t n) {
    if (mBytes.size() - mPos < n) return false;
    std::memcpy(out, mBytes.data() + mPos, n);
    mPos += n;
    return true;
  }
  bool u32(uint32_t& v) { return read(&v, sizeof v); }
  bool bytes(std::vector<uint8_t>& out, size_t n) {
    if (mBytes.size() - mPos < n) return false;
    out.assign(mBytes.begin() + std::ptrdiff_t(mPos), mBytes.begin() + std::ptrdiff_t(mPos + n));
    mPos += n;
    return true;
  }
  size_t position() const { return mPos; }

private:
  const std::vector<uint8_t>& mBytes;
  size_t mPos = 0;
};

void append(std::string& out, const void* data, size_t n) {
  out.append(static_cast<const char*>(data), n);
}

}  // namespace

std::optional<CacheEntry> readCacheEntry(const fs::path& path, const std::string& key,
                                         uint32_t shapeSize, uint32_t detailSize,
                                         uint32_t curlSize) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  std::vector<uint8_t> bytes;
  try {
    bytes = readBinaryFile(path);
  } catch (const Error&) {
    return std::nullopt;
  }
  // The exact size first: a truncated or padded file is rejected before anything is copied.
  const size_t expected = sizeof kMagic + 4 + 4 + key.size() + 12 + volumeBytes(shapeSize) +
                          volumeBytes(detailSize) + size_t(curlSize) * curlSize * 4 + 8;
  if (bytes.size() != expected) return std::nullopt;
  Reader in(bytes);
  char magic[sizeof kMagic];
  uint32_t version = 0, keyLength = 0, sizes[3] = {};
  if (!in.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0 ||
      !in.u32(version) || version != kVersion || !in.u32(keyLength) || keyLength != key.size())
    return std::nullopt;
  std::vector<uint8_t> storedKey;
  if (!in.bytes(storedKey, keyLength) ||
      std::string_view(reinterpret_cast<const char*>(storedKey.data()), storedKey.size()) != key)
    return std::nullopt;
  for (uint32_t& s : sizes)
    if (!in.u32(s)) return std::nullopt;
  if (sizes[0] != shapeSize || sizes[1] != detailSize || sizes[2] != curlSize) return std::nullopt;
  CacheEntry entry;
  entry.shape.size = shapeSize;
  entry.detail.size = detailSize;
  entry.curlSize = curlSize;
  const size_t payloadEnd = bytes.size() - 8;
  uint64_t checksum = 0;
  std::memcpy(&checksum, bytes.data() + payloadEnd, sizeof checksum);
  if (hash64({reinterpret_cast<const char*>(bytes.data()), payloadEnd}) != checksum)
    return std::nullopt;
  if (!in.bytes(entry.shape.rgba, volumeBytes(shapeSize)) ||
      !in.bytes(entry.detail.rgba, volumeBytes(detailSize)) ||
      !in.bytes(entry.curl, size_t(curlSize) * curlSize * 4) || in.position() != payloadEnd)
    return std::nullopt;
  return entry;
}

void writeCacheEntry(const fs::path& path, const std::string& key, const CacheEntry& entry) {
  if (entry.shape.rgba.size() != volumeBytes(entry.shape.size) ||
      entry.detail.rgba.size() != volumeBytes(entry.detail.size) ||
      entry.curl.size() != size_t(entry.curlSize) * entry.curlSize * 4)
    internalError("cloud-noise cache entry of the wrong size");
  std::string out;
  out.reserve(entry.shape.rgba.size() + entry.detail.rgba.size() + entry.curl.size() + 64 +
              key.size());
  append(out, kMagic, sizeof kMagic);
  append(out, &kVersion, 4);
  const auto keyLength = static_cast<uint32_t>(key.size());
  append(out, &keyLength, 4);
  out += key;
  const uint32_t sizes[3] = {entry.shape.size, entry.detail.size, entry.curlSize};
  append(out, sizes, sizeof sizes);
  append(out, entry.shape.rgba.data(), entry.shape.rgba.size());
  append(out, entry.detail.rgba.data(), entry.detail.rgba.size());
  append(out, entry.curl.data(), entry.curl.size());
  const uint64_t checksum = hash64(out);
  append(out, &checksum, sizeof checksum);
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) inputError(path.parent_path().string() + ": cannot create folder: " + ec.message());
  writeFileAtomic(path, out);
}

}  // namespace sky::cloud_noise
