#include "engine/core/paths.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>

namespace sky {
namespace fs = std::filesystem;

namespace {
const char* env(const char* name) {
  const char* v = std::getenv(name);
  return (v && *v) ? v : nullptr;
}
}  // namespace

fs::path dataRoot() {
  if (const char* v = env("SKY_DATA_DIR")) return v;
  return SKY_DATA_DIR_DEFAULT;
}

fs::path shaderDir() {
  if (const char* v = env("SKY_SHADER_DIR")) return v;
  return dataRoot() / "shaders";
}

fs::path configDir() {
  return dataRoot() / "configs";
}

fs::path cacheDir() {
  fs::path dir;
  if (const char* v = env("SKY_CACHE_DIR"))
    dir = v;
  else if (const char* x = env("XDG_CACHE_HOME"))
    dir = fs::path(x) / "skylayers";
  else if (const char* h = env("HOME"))
    dir = fs::path(h) / ".cache" / "skylayers";
  else
    dir = fs::temp_directory_path() / "skylayers-cache";
  std::error_code ec;
  fs::create_directories(dir, ec);  // a failure shows up later as a cache miss, not an error
  return dir;
}

namespace {
std::mutex gCacheFailureMutex;
std::string gCacheFailure;  // the first failed cache write, "" while none has failed
}  // namespace

void noteCacheWriteFailed(const std::string& error) {
  std::lock_guard<std::mutex> lock(gCacheFailureMutex);
  if (gCacheFailure.empty()) gCacheFailure = error.empty() ? "a write failed" : error;
}

CacheStatus cacheStatus() {
  static const CacheStatus probed = [] {
    CacheStatus s;
    s.folder = cacheDir();
    std::error_code ec;
    fs::create_directories(s.folder, ec);
    if (!fs::is_directory(s.folder)) {
      s.reason = "cannot create the folder" + (ec ? ": " + ec.message() : std::string());
      return s;
    }
    const fs::path probe = s.folder / (".probe-" + std::to_string(::getpid()));
    std::ofstream out(probe, std::ios::binary);
    if (!out) {
      s.reason = std::strerror(errno);
      return s;
    }
    out.close();
    fs::remove(probe, ec);
    s.writable = true;
    return s;
  }();
  CacheStatus status = probed;
  std::lock_guard<std::mutex> lock(gCacheFailureMutex);
  if (status.writable && !gCacheFailure.empty()) {
    status.writable = false;
    status.reason = gCacheFailure;
  }
  return status;
}

const char* skylayersVersion() {
  return SKY_VERSION;
}

}  // namespace sky
