#pragma once
// GLSL compute shaders -> SPIR-V 1.6 (Vulkan 1.3) at run time with glslang, with #include,
// defines, one-line errors, an on-disk SPIR-V cache and reflection.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/paths.h"
#include "engine/shader/spirv_reflect.h"

namespace sky {

struct ShaderDefine {
  std::string name;
  std::string value;
};

struct CompiledShader {
  std::filesystem::path path;  // absolute path of the main file
  std::vector<uint32_t> spirv;
  ShaderReflection reflection;
  uint64_t sourceHash = 0;  // the cache key: preprocessed source + defines + compiler version
  bool fromCache = false;
  std::vector<std::filesystem::path> dependencies;  // main file + every include (for hot reload)
};

// A shader that does not compile. what() is one line, "<file>:<line>: error: <message>"
// plus " (and N more errors)"; log() keeps glslang's full output for a debug view.
class ShaderCompileError : public Error {
public:
  ShaderCompileError(const std::string& message, std::string log)
      : Error(ErrorKind::Internal, message), mLog(std::move(log)) {}
  const std::string& log() const { return mLog; }

private:
  std::string mLog;
};

// Stateless after construction: compile() may be called from several threads at once
// (glslang is initialised once per process, thread-safely, and never finalised).
class ShaderCompiler {
public:
  // Cheap, no file access; both paths are copied (the root made absolute). A nullopt
  // `cacheDirectory` disables the SPIR-V cache; the folder is created on first store.
  explicit ShaderCompiler(std::filesystem::path shaderRoot = shaderDir(),
                          std::optional<std::filesystem::path> cacheDirectory = cacheDir() /
                                                                                "spirv");

  // Any time, any thread; re-reads every file on each call (hot reload just calls it again).
  // Compiles `relativePath` (relative to the root, or absolute) as a compute shader, or loads
  // it from the cache when the preprocessed source matches. Throws ShaderCompileError
  // (Internal) on compile errors, Error (Internal) for a missing main file or a bad define.
  CompiledShader compile(const std::filesystem::path& relativePath,
                         const std::vector<ShaderDefine>& defines = {});

  // Fixed at construction.
  const std::filesystem::path& root() const { return mRoot; }
  const std::optional<std::filesystem::path>& cacheDirectory() const { return mCacheDir; }

  // Identifies glslang's version and our target/cache settings; part of every cache key.
  static const std::string& compilerVersion();

private:
  std::filesystem::path mRoot;
  std::string mRootName;  // the root folder's own name, prefix of reported paths
  std::optional<std::filesystem::path> mCacheDir;
};

}  // namespace sky
