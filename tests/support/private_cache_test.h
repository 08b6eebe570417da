#pragma once
// A GPU test fixture with a cache folder of its own (SKY_CACHE_DIR pointed at a fresh temporary
// folder, restored afterwards), for bakes that store their results on disk: every test starts
// with an empty cache and tests running in parallel do not see each other's entries. The SPIR-V
// cache stays shared. Provides the shader compiler and graph runtime the bakes take.
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include <unistd.h>

#include "engine/core/paths.h"
#include "engine/graph/graph_runtime.h"
#include "engine/shader/shader_compiler.h"
#include "gpu_test.h"

namespace sky::test {

class PrivateCacheTest : public GpuTest {
protected:
  // `prefix` names the temporary folders ("sky-high-clouds" -> sky-high-clouds-<pid>-<n>).
  explicit PrivateCacheTest(std::string prefix) : mPrefix(std::move(prefix)) {}

  void SetUp() override {
    mSpirvCache = cacheDir() / "spirv";
    const char* old = std::getenv("SKY_CACHE_DIR");
    mHadCache = old != nullptr;
    if (old) mOldCache = old;
    static std::atomic<int> counter{0};
    mCache = std::filesystem::temp_directory_path() /
             (mPrefix + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(mCache);
    std::filesystem::create_directories(mCache);
    setenv("SKY_CACHE_DIR", mCache.c_str(), 1);
    mCompiler = std::make_unique<ShaderCompiler>(shaderDir(), mSpirvCache);
    mRuntime = std::make_unique<GraphRuntime>(ctx());
  }
  void TearDown() override {
    mRuntime.reset();
    if (mHadCache)
      setenv("SKY_CACHE_DIR", mOldCache.c_str(), 1);
    else
      unsetenv("SKY_CACHE_DIR");
    std::error_code ec;
    std::filesystem::remove_all(mCache, ec);
  }

public:
  const std::filesystem::path& cache() const { return mCache; }
  GraphRuntime& runtime() { return *mRuntime; }
  ShaderCompiler& compiler() { return *mCompiler; }

private:
  std::string mPrefix;
  std::filesystem::path mSpirvCache, mCache;
  std::string mOldCache;
  bool mHadCache = false;
  std::unique_ptr<ShaderCompiler> mCompiler;
  std::unique_ptr<GraphRuntime> mRuntime;
};

}  // namespace sky::test
