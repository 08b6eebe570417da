#include "engine/core/paths.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <vector>

namespace sky {
namespace fs = std::filesystem;

namespace {
const char* env(const char* name) {
  const char* v = std::getenv(name);
  return (v && *v) ? v : nullptr;
}
// The data an installed copy carries: PREFIX/share/skylayers beside PREFIX/lib or
// PREFIX/bin (cmake --install, lib/CMakeLists.txt), found from where this code was loaded from.
// dladdr names the shared library (libskylayers.so, the installed package's); for a program linked
// statically against the modules (an installed skyrender) it may name no file, so the executable is
// tried too.
fs::path installedDataRoot() {
  std::vector<fs::path> binaries;
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&installedDataRoot), &info) && info.dli_fname &&
      *info.dli_fname)
    binaries.emplace_back(info.dli_fname);
  binaries.emplace_back("/proc/self/exe");
  for (const fs::path& binary : binaries) {
    std::error_code ec;
    const fs::path real = fs::canonical(binary, ec);
    if (ec) continue;
    // PREFIX/bin/x, PREFIX/lib/x or PREFIX/lib/<multiarch>/x (GNUInstallDirs on Debian).
    fs::path prefix = real.parent_path();
    for (int up = 0; up < 2 && prefix.has_relative_path(); ++up) {
      prefix = prefix.parent_path();
      const fs::path share = prefix / "share" / "skylayers";
      if (fs::is_directory(share / "shaders", ec) && fs::is_directory(share / "configs", ec))
        return share;
    }
  }
  return {};
}
}  // namespace

fs::path dataRoot() {
  if (const char* v = env("SKY_DATA_DIR")) return v;
  // Looked up once: the answer cannot change while the process runs.
  static const fs::path installed = installedDataRoot();
  if (!installed.empty()) return installed;
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
