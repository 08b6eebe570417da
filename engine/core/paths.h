#pragma once
// Where run-time data lives. shaders/ and configs/ are read from the data root:
// $SKY_DATA_DIR if set; else, for an installed copy, PREFIX/share/skylayers next to the
// library or program's PREFIX/lib or PREFIX/bin; else the source tree it was built from.
#include <filesystem>
#include <string>

namespace sky {

std::filesystem::path dataRoot();
std::filesystem::path shaderDir();  // $SKY_SHADER_DIR or dataRoot()/shaders
std::filesystem::path configDir();  // dataRoot()/configs
// Caches (SPIR-V, later baked textures): $SKY_CACHE_DIR, else $XDG_CACHE_HOME/skylayers,
// else ~/.cache/skylayers. Created on first use.
std::filesystem::path cacheDir();

// Whether cacheDir() takes files: checked once per process by writing a probe file, and
// false from the first cache write that failed (a full disk takes a probe but not a 30 MB
// bake: issue 31, 10). A cache that cannot be written only makes runs slower (bakes and
// shader compiles repeat), so callers warn rather than fail.
struct CacheStatus {
  std::filesystem::path folder;
  bool writable = false;
  std::string reason;  // why not, when not writable
};
CacheStatus cacheStatus();
// Records that a write into the cache failed, with the error; the first one is kept.
void noteCacheWriteFailed(const std::string& error);

// The project's version (CMake's PROJECT_VERSION), for --version and render reports.
const char* skylayersVersion();

}  // namespace sky
