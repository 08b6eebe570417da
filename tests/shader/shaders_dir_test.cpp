// Every shader the project ships must compile: shaders/**/*.comp, and every shared header in
// shaders/common/ on its own (so a header that only works after some other include fails).
#include <algorithm>

#include "engine/core/paths.h"
#include "engine/shader/shader_compiler.h"
#include "tests/shader/shader_test_util.h"

namespace sky {
namespace {
namespace fs = std::filesystem;
using test::ScratchDir;
using test::writeText;

std::vector<fs::path> filesUnder(const fs::path& dir, std::initializer_list<const char*> exts) {
  std::vector<fs::path> out;
  if (!fs::is_directory(dir)) return out;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir))
    for (const char* ext : exts)
      if (e.is_regular_file() && e.path().extension() == ext) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(ProjectShaders, EveryComputeShaderInShadersCompiles) {
  const std::vector<fs::path> shaders = filesUnder(shaderDir(), {".comp"});
  ASSERT_FALSE(shaders.empty()) << "no .comp files under " << shaderDir();
  ShaderCompiler compiler(shaderDir(), std::nullopt);  // no cache: really compile each one
  for (const fs::path& path : shaders) {
    SCOPED_TRACE(path.string());
    try {
      CompiledShader s = compiler.compile(path);
      EXPECT_FALSE(s.spirv.empty());
      const auto& size = s.reflection.localSize;
      EXPECT_GT(size[0] * size[1] * size[2], 0u);
    } catch (const ShaderCompileError& e) {
      ADD_FAILURE() << e.what() << "\n" << e.log();
    }
  }
}

TEST(ProjectShaders, EveryCommonHeaderCompilesOnItsOwn) {
  const fs::path common = shaderDir() / "common";
  const std::vector<fs::path> headers = filesUnder(common, {".glsl", ".h"});
  ASSERT_FALSE(headers.empty()) << "no .glsl/.h files under " << common;
  ScratchDir dir("common-wrap");
  ShaderCompiler compiler(shaderDir(), std::nullopt);
  for (const fs::path& header : headers) {
    const std::string rel = header.lexically_relative(shaderDir()).generic_string();
    SCOPED_TRACE(rel);
    // The wrapper sits outside the root, so <...> resolves the header under shaders/ exactly
    // as a pass shader would.
    const fs::path wrapper = dir.path() / (header.stem().string() + "_wrapper.comp");
    writeText(wrapper, "#version 460\n#include <" + rel + ">\n#include <" + rel +
                           ">\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
    try {
      CompiledShader s = compiler.compile(wrapper);
      EXPECT_TRUE(std::find(s.dependencies.begin(), s.dependencies.end(), header) !=
                  s.dependencies.end());
    } catch (const ShaderCompileError& e) {
      ADD_FAILURE() << e.what() << "\n" << e.log();
    }
  }
}

}  // namespace
}  // namespace sky
