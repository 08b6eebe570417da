#include "engine/core/files.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "engine/core/error.h"

namespace sky {
namespace fs = std::filesystem;

std::string readTextFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) inputError(path.string() + ": cannot open file: " + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) inputError(path.string() + ": read error");
  return ss.str();
}

std::vector<uint8_t> readBinaryFile(const fs::path& path) {
  std::string text = readTextFile(path);
  return std::vector<uint8_t>(text.begin(), text.end());
}

void writeFileAtomic(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  static std::atomic<unsigned> counter{0};
  fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  // The temporary keeps the final extension so format libraries that look at it still work.
  fs::path tmp = dir / (".tmp-" + std::to_string(::getpid()) + "-" +
                        std::to_string(counter++) + "-" + path.filename().string());
  try {
    write(tmp);
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) inputError(path.string() + ": cannot write file: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

void writeFileAtomic(const fs::path& path, std::string_view bytes) {
  writeFileAtomic(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) inputError(path.string() + ": cannot write file: " + std::strerror(errno));
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) inputError(path.string() + ": write failed (disk full?)");
  });
}

uint64_t hash64(std::string_view bytes, uint64_t seed) {
  uint64_t h = seed;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

std::string hex64(uint64_t value) {
  static const char* kDigits = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 15; i >= 0; --i, value >>= 4) s[static_cast<size_t>(i)] = kDigits[value & 0xf];
  return s;
}

}  // namespace sky
