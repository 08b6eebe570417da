#pragma once
// SHA-256 (FIPS 180-4), for the checksums a dataset's manifest lists (docs/datasets.md): the
// same digest `sha256sum` prints, so a user can check a sample with the tools they have.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace sky {

class Sha256 {
public:
  Sha256();
  void update(const void* data, size_t size);
  void update(std::string_view text) { update(text.data(), text.size()); }
  // The digest as 64 lowercase hex digits; the object is spent afterwards.
  std::string hex();

private:
  void block(const uint8_t* p);
  uint32_t mState[8];
  uint8_t mBuffer[64];
  size_t mBuffered = 0;
  uint64_t mLength = 0;  // bytes
};

std::string sha256Hex(std::string_view data);
// The digest of a file's bytes; a file that cannot be read is a BadInput error naming it.
std::string sha256File(const std::filesystem::path& path);

}  // namespace sky
